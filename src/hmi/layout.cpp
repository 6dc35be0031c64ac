#include "hmi/layout.hpp"

#include <algorithm>

#include "plant/robot.hpp"

namespace virtcom::hmi {

namespace {
constexpr double kMarginMm = 200;   // around a robot's locations
constexpr double kGapMm = 300;      // between boxes
constexpr double kBoxW = 600, kBoxH = 400;  // devices without coordinates of their own
constexpr int kPerRow = 4;

// A robot's box around its locations (and its base at the origin).
Place robotPlace(const plant::Robot& robot, double left) {
  double minX = 0, maxX = 0, minY = 0, maxY = 0;
  for (const auto& loc : robot.params().locations) {
    minX = std::min(minX, loc.pos[0] * 1000);
    maxX = std::max(maxX, loc.pos[0] * 1000);
    minY = std::min(minY, loc.pos[1] * 1000);
    maxY = std::max(maxY, loc.pos[1] * 1000);
  }
  Place p;
  p.x = left;
  p.y = 0;
  p.w = maxX - minX + 2 * kMarginMm;
  p.h = maxY - minY + 2 * kMarginMm;
  p.originX = left + kMarginMm - minX;
  p.originY = kMarginMm - minY;
  return p;
}
}  // namespace

std::vector<Place> placeDevices(const cell::Cell& cell) {
  std::vector<Place> places(cell.devices.size());
  double left = 0;
  bool anyRobot = false;
  for (size_t i = 0; i < cell.devices.size(); ++i)
    if (const auto* robot = dynamic_cast<const plant::Robot*>(cell.devices[i].get())) {
      places[i] = robotPlace(*robot, left);
      left += places[i].w + kGapMm;
      anyRobot = true;
    }
  int slot = 0;
  const double top = anyRobot ? -kGapMm : 0;
  for (size_t i = 0; i < cell.devices.size(); ++i) {
    if (dynamic_cast<const plant::Robot*>(cell.devices[i].get())) continue;
    Place& p = places[i];
    p.w = kBoxW;
    p.h = kBoxH;
    p.x = (slot % kPerRow) * (kBoxW + kGapMm);
    p.y = top - (slot / kPerRow + 1) * (kBoxH + kGapMm) + kGapMm;
    p.originX = p.x;
    p.originY = p.y;
    ++slot;
  }
  return places;
}

}  // namespace virtcom::hmi

#include "hmi/layout.hpp"

#include <algorithm>
#include <limits>

#include "plant/robot.hpp"

namespace virtcom::hmi {

namespace {
constexpr double kMarginMm = 200;   // around a robot's locations
constexpr double kGapMm = 300;      // between boxes
constexpr double kBoxW = 600, kBoxH = 400;  // devices without coordinates of their own
constexpr int kPerRow = 4;

// A robot's box around its locations (and its base at the origin), its frame's origin at
// (originX, originY).
Place robotPlace(const plant::Robot& robot, double originX, double originY) {
  double minX = 0, maxX = 0, minY = 0, maxY = 0;
  for (const auto& loc : robot.params().locations) {
    minX = std::min(minX, loc.pos[0] * 1000);
    maxX = std::max(maxX, loc.pos[0] * 1000);
    minY = std::min(minY, loc.pos[1] * 1000);
    maxY = std::max(maxY, loc.pos[1] * 1000);
  }
  Place p;
  p.x = originX + minX - kMarginMm;
  p.y = originY + minY - kMarginMm;
  p.w = maxX - minX + 2 * kMarginMm;
  p.h = maxY - minY + 2 * kMarginMm;
  p.originX = originX;
  p.originY = originY;
  return p;
}

// The automatic plan: robots side by side, every other device in a grid below them.
std::vector<Place> automaticPlaces(const cell::Cell& cell) {
  std::vector<Place> places(cell.devices.size());
  double left = 0;
  bool anyRobot = false;
  for (size_t i = 0; i < cell.devices.size(); ++i)
    if (const auto* robot = dynamic_cast<const plant::Robot*>(cell.devices[i].get())) {
      const Place around = robotPlace(*robot, 0, 0);
      places[i] = robotPlace(*robot, left - around.x, -around.y);
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

// `hmi: devices:` over the automatic place: a robot's base moves its box with it; x/y and w/h
// set the box itself.
Place placed(const cell::DevicePlacement& given, const plant::Device& device, Place p) {
  const auto* robot = dynamic_cast<const plant::Robot*>(&device);
  if (robot && given.baseX) p = robotPlace(*robot, *given.baseX * 1000, *given.baseY * 1000);
  if (given.x) {
    const double dx = *given.x * 1000 - p.x, dy = *given.y * 1000 - p.y;
    p.x += dx;
    p.y += dy;
    if (!robot || !given.baseX) {  // the frame moves with the box unless the base was given
      p.originX += dx;
      p.originY += dy;
    }
  }
  if (given.w) p.w = *given.w * 1000;
  if (given.h) p.h = *given.h * 1000;
  return p;
}
}  // namespace

std::vector<Place> placeDevices(const cell::Cell& cell) {
  std::vector<Place> places = automaticPlaces(cell);
  std::vector<bool> isPlaced(places.size(), false);
  for (const cell::DevicePlacement& given : cell.hmi.devices) {
    places[given.device] = placed(given, *cell.devices[given.device], places[given.device]);
    isPlaced[given.device] = given.x || given.baseX;
  }
  // Devices the file does not place go below those it does, so nothing overlaps.
  double placedBottom = std::numeric_limits<double>::infinity(), autoTop = -std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < places.size(); ++i) {
    if (isPlaced[i]) placedBottom = std::min(placedBottom, places[i].y);
    else autoTop = std::max(autoTop, places[i].y + places[i].h);
  }
  if (placedBottom == std::numeric_limits<double>::infinity() || autoTop == -std::numeric_limits<double>::infinity()) return places;
  const double shift = placedBottom - kGapMm - autoTop;
  for (size_t i = 0; i < places.size(); ++i)
    if (!isPlaced[i]) {
      places[i].y += shift;
      places[i].originY += shift;
    }
  return places;
}

}  // namespace virtcom::hmi

#include "hmi/cell_model.hpp"

#include <cmath>

#include "hmi/layout.hpp"
#include "plant/axis.hpp"
#include "plant/conveyor.hpp"
#include "plant/press.hpp"
#include "plant/robot.hpp"

namespace virtcom::hmi {

namespace {

using Json = nlohmann::json;

Json robotGeometry(const plant::Robot& robot, const cell::Cell& cell) {
  Json locations = Json::array();
  for (const auto& loc : robot.params().locations)
    locations.push_back({{"name", loc.name},
                         {"x", loc.pos[0] * 1000},
                         {"y", loc.pos[1] * 1000},
                         {"z", loc.pos[2] * 1000},
                         {"zone", loc.zone >= 0 ? Json(cell.world.zoneName(static_cast<uint32_t>(loc.zone))) : Json()}});
  Json tools = Json::array();
  for (const auto& tool : robot.params().tools) tools.push_back(tool.name);
  return {{"locations", locations}, {"tools", tools}};
}

// What the layout view needs beyond the ports to draw the device's kind.
Json geometry(const plant::Device& d, const cell::Cell& cell) {
  if (const auto* robot = dynamic_cast<const plant::Robot*>(&d)) return robotGeometry(*robot, cell);
  if (const auto* axis = dynamic_cast<const plant::Axis*>(&d))
    return {{"minPosition", axis->params().minPosition * 1000}, {"maxPosition", axis->params().maxPosition * 1000}};
  if (const auto* press = dynamic_cast<const plant::Press*>(&d)) return {{"stroke", press->params().strokeM * 1000}};
  if (const auto* conveyor = dynamic_cast<const plant::Conveyor*>(&d)) {
    const auto& p = conveyor->params();
    Json sensors = Json::array();
    for (const auto& s : p.sensors) sensors.push_back({{"name", s.name}, {"position", static_cast<double>(s.positionNm) * 1e-6}});
    // The bins (pushers in order, then the belt end with discharge) count their parts on the
    // ports `<bin>_<kind>`; the page reads those signals.
    Json pushers = Json::array();
    for (const auto& s : p.pushers) pushers.push_back({{"name", s.name}, {"position", static_cast<double>(s.positionNm) * 1e-6}});
    Json kinds = p.kinds.empty() ? Json::array({"parts"}) : Json(p.kinds);
    return {{"length", static_cast<double>(p.lengthNm) * 1e-6},
            {"partLength", static_cast<double>(p.partLengthNm) * 1e-6},
            {"sensors", sensors},
            {"pushers", pushers},
            {"kinds", kinds},
            {"discharge", p.discharge}};
  }
  return Json::object();
}

// What `hmi: devices:` says about device `index` beyond its place.
const cell::DevicePlacement* placement(const cell::Cell& cell, size_t index) {
  for (const cell::DevicePlacement& p : cell.hmi.devices)
    if (p.device == index) return &p;
  return nullptr;
}

// Metres as millimetres rounded to the micrometre: "3800 mm" is sent as 3800, not 3800.0000000000005.
double mm(double metres) { return std::round(metres * 1e6) / 1000; }

Json shapeJson(const cell::HmiShape& s) {
  Json j = {{"kind", cell::shapeKindName(s.kind)}, {"x", mm(s.x)}, {"y", mm(s.y)}, {"label", s.label}, {"colour", s.colour}};
  switch (s.kind) {
    case cell::HmiShape::Kind::Rect: j["w"] = mm(s.w); j["h"] = mm(s.h); break;
    case cell::HmiShape::Kind::Circle: j["r"] = mm(s.r); break;
    case cell::HmiShape::Kind::Line: j["x2"] = mm(s.x2); j["y2"] = mm(s.y2); break;
    case cell::HmiShape::Kind::Text: break;
  }
  return j;
}

Json deviceJson(const plant::Device& d, const Place& place, const cell::DevicePlacement* given, const cell::Cell& cell) {
  Json ports = Json::array();
  for (size_t i = 0; i < d.ports().size(); ++i) {
    const plant::PortSpec& p = d.ports()[i];
    ports.push_back({{"name", p.name},
                     {"tag", d.tag(i)},
                     {"type", elemTypeInfo(p.type).name},
                     {"dir", p.dir == plant::PortDir::In ? "in" : "out"}});
  }
  const DeviceInfo& info = cell.trace.devices[d.traceIndex()];
  return {{"name", d.name()},
          {"label", given && !given->label.empty() ? given->label : d.name()},
          {"layoutGroup", given ? given->group : std::string()},
          {"type", d.type()},
          {"group", info.group},
          {"trace", d.traceIndex()},
          {"ports", ports},
          {"place", {{"x", place.x}, {"y", place.y}, {"w", place.w}, {"h", place.h}, {"originX", place.originX}, {"originY", place.originY}}},
          {"geometry", geometry(d, cell)}};
}

}  // namespace

Json cellModel(const cell::Cell& cell, int64_t baseTickNs) {
  std::vector<Place> places = placeDevices(cell);
  Json devices = Json::array();
  for (size_t i = 0; i < cell.devices.size(); ++i) devices.push_back(deviceJson(*cell.devices[i], places[i], placement(cell, i), cell));
  Json shapes = Json::array();
  for (const cell::HmiShape& s : cell.hmi.shapes) shapes.push_back(shapeJson(s));
  Json zones = Json::array();
  for (uint32_t z = 0; z < cell.world.zoneCount(); ++z) zones.push_back(cell.world.zoneName(z));
  Json signals = Json::array();
  for (TagId id = 0; id < cell.bus.size(); ++id) signals.push_back({{"name", cell.bus.name(id)}, {"type", elemTypeInfo(cell.bus.type(id)).name}});
  return {{"name", cell.name},
          {"baseTickNs", baseTickNs},
          {"hasPlc", cell.module != nullptr},
          {"devices", devices},
          {"zones", zones},
          {"labels", cell.trace.labels},
          {"signals", signals},
          {"shapes", shapes}};
}

}  // namespace virtcom::hmi

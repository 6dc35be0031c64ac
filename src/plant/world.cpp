#include "plant/world.hpp"

namespace virtcom::plant {

uint32_t World::fact(const std::string& name) {
  for (size_t i = 0; i < factNames_.size(); ++i)
    if (factNames_[i] == name) return static_cast<uint32_t>(i);
  factNames_.push_back(name);
  facts_.push_back(0);
  return static_cast<uint32_t>(facts_.size() - 1);
}

uint32_t World::vessel(const std::string& name, SourceLocation use) {
  for (size_t i = 0; i < vessels_.size(); ++i)
    if (vessels_[i].name == name) return static_cast<uint32_t>(i);
  vessels_.push_back({});
  vessels_.back().name = name;
  vessels_.back().firstUse = use;
  return static_cast<uint32_t>(vessels_.size() - 1);
}

size_t World::addFeed(uint32_t id) {
  vessels_[id].feeds.emplace_back();
  return vessels_[id].feeds.size() - 1;
}

std::vector<uint32_t> World::undefinedVessels() const {
  std::vector<uint32_t> out;
  for (size_t i = 0; i < vessels_.size(); ++i)
    if (!vessels_[i].defined) out.push_back(static_cast<uint32_t>(i));
  return out;
}

uint32_t World::zone(const std::string& name) {
  for (size_t i = 0; i < zoneNames_.size(); ++i)
    if (zoneNames_[i] == name) return static_cast<uint32_t>(i);
  zoneNames_.push_back(name);
  occupants_.emplace_back();
  occupants_.back().reserve(8);
  zoneLabels_.push_back(trace_.internLabel(name));
  return static_cast<uint32_t>(zoneNames_.size() - 1);
}

bool World::occupies(uint32_t zone, uint32_t device) const {
  for (const auto& o : occupants_[zone])
    if (o.device == device) return true;
  return false;
}

bool World::enterZone(uint32_t zone, uint32_t device, uint32_t activityLabel, int64_t nowNs) {
  auto& occ = occupants_[zone];
  ++changes_;
  for (auto& o : occ)
    if (o.device == device) {
      o.label = activityLabel;
      return true;
    }
  bool clear = true;
  for (const auto& o : occ) {
    CollisionRecord c;
    c.timeNs = nowNs;
    c.zone = zoneLabels_[zone];
    c.deviceA = o.device;
    c.deviceB = device;
    c.activityA = o.label;
    c.activityB = activityLabel;
    trace_.collisions.push_back(c);
    collided_ = true;
    clear = false;
  }
  occ.push_back({device, activityLabel});
  return clear;
}

void World::leaveZone(uint32_t zone, uint32_t device) {
  auto& occ = occupants_[zone];
  for (size_t i = 0; i < occ.size(); ++i)
    if (occ[i].device == device) {
      ++changes_;
      occ[i] = occ.back();
      occ.pop_back();
      return;
    }
}

}  // namespace virtcom::plant

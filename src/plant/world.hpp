#pragma once
// The shared physical state of a simulated cell that devices act on: named facts about the
// workpiece and the cell (pinPlaced, insertLocked, ...), shared-workspace zones with their
// occupants and the vessels of tanks (vessel.hpp). Names are interned at load time; the per-tick
// path uses ids only.
#include <cstdint>
#include <string>
#include <vector>

#include "core/trace.hpp"
#include "plant/vessel.hpp"

namespace virtcom::plant {

class World {
 public:
  explicit World(Trace& trace) : trace_(trace) {}

  // ---- facts (load time: ids; run time: values) ----
  uint32_t fact(const std::string& name);       // creates it (false) if new
  bool hasFact(uint32_t id) const { return facts_[id] != 0; }
  void setFact(uint32_t id, bool value) {
    const uint8_t v = value ? 1 : 0;
    changes_ += facts_[id] != v;
    facts_[id] = v;
  }
  const std::string& factName(uint32_t id) const { return factNames_[id]; }
  size_t factCount() const { return facts_.size(); }
  // Initial facts (set before the run, e.g. from the cell file's `world:` section).
  void setInitial(uint32_t id, bool value) { facts_[id] = value ? 1 : 0; }

  // ---- zones ----
  uint32_t zone(const std::string& name);       // creates it if new
  size_t zoneCount() const { return zoneNames_.size(); }
  const std::string& zoneName(uint32_t id) const { return zoneNames_[id]; }
  // `device` (a Trace device index) starts occupying `zone` while doing `activityLabel`.
  // If another device is in it, a collision is recorded in the trace (once per pair and entry)
  // and false is returned. A device may enter a zone it already occupies.
  bool enterZone(uint32_t zone, uint32_t device, uint32_t activityLabel, int64_t nowNs);
  void leaveZone(uint32_t zone, uint32_t device);
  bool occupies(uint32_t zone, uint32_t device) const;
  // True once any collision happened (the simulation may stop on it).
  bool collided() const { return collided_; }
  // Counts fact changes and zone entries/exits: a device stepped before the one that changed the
  // world sees the change only at the next tick, so event-driven time never skips that tick.
  uint64_t changes() const { return changes_; }

  // ---- vessels (tanks and the devices acting on or sensing them) ----
  // The vessel named `name`, created (undefined) if new; `use` is where a device names it.
  uint32_t vessel(const std::string& name, SourceLocation use);
  Vessel& vesselAt(uint32_t id) { return vessels_[id]; }
  const Vessel& vesselAt(uint32_t id) const { return vessels_[id]; }
  // A new feed slot of vessel `id` for one device (load time); its index in Vessel::feeds.
  size_t addFeed(uint32_t id);
  // The vessels some device names but no tank defines, for the loader to report.
  std::vector<uint32_t> undefinedVessels() const;

  Trace& trace() { return trace_; }

 private:
  struct Occupant {
    uint32_t device;
    uint32_t label;
  };
  Trace& trace_;
  std::vector<uint8_t> facts_;
  std::vector<std::string> factNames_;
  std::vector<std::string> zoneNames_;
  std::vector<uint32_t> zoneLabels_;              // trace label of each zone name, interned at load
  std::vector<std::vector<Occupant>> occupants_;  // per zone; reserved at load, at most #devices
  std::vector<Vessel> vessels_;
  bool collided_ = false;
  uint64_t changes_ = 0;
};

}  // namespace virtcom::plant

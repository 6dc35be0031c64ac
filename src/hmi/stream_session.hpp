#pragma once
// One viewer's live stream (GET /api/stream): frames of what changed since that viewer's own
// previous frame, so each client gets only news, at its own rate, and a slow one simply gets
// fewer frames (it never holds anything up). The first frame carries everything. The frame
// schema is in docs/hmi.md.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hmi/live_state.hpp"
#include "hmi/variable_catalog.hpp"
#include "lang/sfc/step_monitor.hpp"

namespace virtcom::hmi {

class StreamSession {
 public:
  // `live`, `catalog`, `tagTypes` (the type of each tag) and `steps` (the SFC panel's) must
  // outlive the session. `watch`: PLC variables shown with their values; unknown names are
  // listed in the first frame.
  StreamSession(const LiveState& live, const VariableCatalog& catalog, const std::vector<ElemType>& tagTypes,
                const std::vector<sfc::StepVariable>& steps, const std::vector<std::string>& watch);

  // The next frame's JSON text, or "" when nothing was published since the last one.
  std::string nextFrame();

 private:
  struct Watched {
    std::string name;
    bc::VarRef ref;
    std::string last;  // the value text sent last
    bool lastForced = false;
    bool sent = false;
  };

  const LiveState& live_;
  const VariableCatalog& catalog_;
  // A reset started a new run: everything is sent again, as in a first frame.
  void startOver();
  nlohmann::json activeSteps(const Snapshot& s) const;
  nlohmann::json changedRules(const Snapshot& s);
  nlohmann::json changedBelts(const Snapshot& s);
  nlohmann::json changedStations(const Snapshot& s);

  const std::vector<ElemType>& tagTypes_;
  const std::vector<sfc::StepVariable>& steps_;
  std::vector<Watched> watched_;
  std::vector<std::string> unknown_;
  uint64_t seq_ = 0;
  bool first_ = true;
  std::vector<uint64_t> tags_;          // values sent last
  size_t activities_ = 0;               // activities sent so far
  std::vector<uint32_t> open_;          // sent while running: resent once they end
  size_t faults_ = 0, collisions_ = 0;
  std::vector<std::string> forced_;
  std::vector<int32_t> injected_;
  bool ended_ = false;
  uint32_t run_ = 0;                    // Snapshot::run of the frames sent
  nlohmann::json stepsSent_;            // the active steps sent last
  std::vector<plc::RuleFiring> rules_;  // the firings sent last
  std::vector<BeltParts> belts_;        // the parts sent last
  std::vector<Station> stations_;       // the stations sent last
};

}  // namespace virtcom::hmi

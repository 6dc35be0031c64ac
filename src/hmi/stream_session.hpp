#pragma once
// One viewer's live stream (GET /api/stream): frames of what changed since that viewer's own
// previous frame, so each client gets only news, at its own rate, and a slow one simply gets
// fewer frames (it never holds anything up). The first frame carries everything. The frame
// schema is in docs/hmi.md.
#include <cstdint>
#include <string>
#include <vector>

#include "hmi/live_state.hpp"
#include "hmi/variable_catalog.hpp"

namespace virtcom::hmi {

class StreamSession {
 public:
  // `live`, `catalog` and `tagTypes` (the type of each tag) must outlive the session.
  // `watch`: PLC variables shown with their values; unknown names are listed in the first frame.
  StreamSession(const LiveState& live, const VariableCatalog& catalog, const std::vector<ElemType>& tagTypes,
                const std::vector<std::string>& watch);

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
  const std::vector<ElemType>& tagTypes_;
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
};

}  // namespace virtcom::hmi

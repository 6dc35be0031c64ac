// The client bridge's browse paths (client_bridge.hpp; OPC 10000-4 §5.8.4
// TranslateBrowsePathsToNodeIds): all of them in one request, at start and after each reconnect.
#include <optional>

#include "proto/opcua/client_bridge.hpp"
#include "proto/opcua/services.hpp"

namespace virtcom::proto::opcua {

namespace {

constexpr uint32_t kTranslateRequestId = 554, kTranslateResponseId = 557;
constexpr uint32_t kWholePath = 0xFFFFFFFF;  // a target's RemainingPathIndex: every element followed

}  // namespace

bool ClientBridge::translatePaths(std::vector<Problem>& problems) {
  if (paths_.empty()) return true;
  Writer& w = client_.beginRequest(kTranslateRequestId);
  w.i32(static_cast<int32_t>(paths_.size()));
  for (const PathSignal& p : paths_) encodeBrowsePath(w, p.path);
  auto reply = client_.call(kTranslateResponseId);
  if (!reply) {
    problems.push_back({kNoSignal, "opcua: " + peerText() + " refused resolving the browse paths (TranslateBrowsePathsToNodeIds): " +
                                       reply.error().text + (reply.error().linkLost ? "" : "; name the nodes by node id instead"),
                        Problem::Kind::Link});
    return false;
  }
  uint32_t count = 0;
  if (!reply->arrayLength(count, 8) || count != paths_.size()) {
    problems.push_back({kNoSignal, "opcua: " + peerText() + " answered the browse paths with " + std::to_string(count) + " results for " +
                                       std::to_string(paths_.size()), Problem::Kind::Link});
    return false;
  }
  for (const PathSignal& p : paths_) {
    uint32_t status = 0, targets = 0;
    if (!reply->u32(status) || !reply->arrayLength(targets, 5)) {
      problems.push_back({kNoSignal, "opcua: " + peerText() + " sent a malformed TranslateBrowsePathsToNodeIds response", Problem::Kind::Link});
      return false;
    }
    std::optional<NodeId> found;  // the first target the whole path reaches on this server
    for (uint32_t t = 0; t < targets; ++t) {
      ExpandedNodeId id;
      uint32_t remaining = 0;
      if (!decode(*reply, id) || !reply->u32(remaining)) {
        problems.push_back({kNoSignal, "opcua: " + peerText() + " sent a malformed TranslateBrowsePathsToNodeIds response", Problem::Kind::Link});
        return false;
      }
      if (!found && remaining == kWholePath && id.namespaceUri.empty() && id.serverIndex == 0) found = id.id;
    }
    const BridgeSignal& s = config_.signals[p.signal];
    Slot& slot = slots_[p.signal];
    slot.unresolved = isBad(status) || !found;
    std::vector<uint8_t>& bytes = nodeIds_[p.signal];
    bytes.clear();
    Writer node(bytes);
    encode(node, slot.unresolved ? NodeId{} : *found);
    if (!slot.unresolved || s.optional) continue;
    problems.push_back({p.signal,
                        "opcua: the browse path '" + s.node + "' of '" + s.name + "' leads to no node on the server: " +
                            (isBad(status) ? statusName(status) : std::string("no target of the whole path on this server")) +
                            (s.port.empty() ? "" : " (to wire to " + s.port + ")"),
                        Problem::Kind::Unknown});
  }
  return true;
}

}  // namespace virtcom::proto::opcua

#include "proto/opcua/client_bridge.hpp"

#include <sstream>

#include "core/value_codec.hpp"
#include "proto/opcua/raw_values.hpp"
#include "proto/opcua/services.hpp"

namespace virtcom::proto::opcua {

namespace {

constexpr uint32_t kReadRequestId = 631, kReadResponseId = 634, kWriteRequestId = 673, kWriteResponseId = 676;
constexpr uint8_t kCurrentWrite = 0x02;  // AccessLevel bit (OPC 10000-3 §8.57)

}  // namespace

ClientBridge::ClientBridge(BridgeConfig config)
    : config_(std::move(config)),
      client_(config_.client),
      link_({"opcua", peerText(), "every poll", config_.faultOnLoss, config_.report}) {
  slots_.resize(config_.signals.size());
  for (size_t i = 0; i < slots_.size(); ++i) slots_[i].tag = config_.signals[i].tag;
}

ClientBridge::~ClientBridge() = default;

std::string ClientBridge::peerText() const { return "the OPC UA server at " + config_.client.endpointUrl; }

std::string ClientBridge::updatesText() const {
  std::ostringstream text;
  if (subscribed()) text << "subscribed, published every " << subscription_.intervalMs << " ms";
  else text << "a Read every " << static_cast<double>(config_.pollNs) / 1e6 << " ms";
  return text.str();
}

std::unique_ptr<ClientBridge> ClientBridge::start(BridgeConfig config, TagBus& bus, StartReport& report) {
  std::unique_ptr<ClientBridge> b(new ClientBridge(std::move(config)));
  report.found.clear();  // filled once the server has been asked
  for (size_t i = 0; i < b->config_.signals.size(); ++i) {
    const BridgeSignal& s = b->config_.signals[i];
    std::vector<uint8_t> bytes;
    Writer w(bytes);
    if (isBrowsePath(s.node)) {
      auto path = parseBrowsePath(s.node);
      if (!path) report.problems.push_back({i, "opcua: the browse path " + path.error()});
      else b->paths_.push_back({i, std::move(*path)});
    } else if (auto id = parseNodeId(s.node)) {
      encode(w, *id);
    } else {
      report.problems.push_back({i, "opcua: '" + s.node + "' is not a node id or a browse path (expected e.g. ns=4;s=NAME, ns=2;i=17 or /4:MAIN/4:x)"});
    }
    b->nodeIds_.push_back(std::move(bytes));
  }
  if (!report.problems.empty()) return nullptr;
  if (auto up = b->client_.connect(); !up) {
    report.problems.push_back({kNoSignal, "opcua: cannot connect to " + b->peerText() + ": " + up.error().text, Problem::Kind::Link});
    return nullptr;
  }
  bool ok = b->resolve(bus, true, report.problems);
  for (const Slot& slot : b->slots_) report.found.push_back(slot.exists);
  if (!ok) return nullptr;
  if (auto subscribed = b->subscribe(); !subscribed) {
    report.problems.push_back({kNoSignal, "opcua: " + b->peerText() + " " + subscribed.error(), Problem::Kind::Link});
    return nullptr;
  }
  return b;
}

bool ClientBridge::resolve(TagBus& bus, bool addTags, std::vector<Problem>& problems) {
  const size_t before = problems.size();
  reads_.clear();
  writes_.clear();
  if (slots_.empty()) return true;
  if (!translatePaths(problems)) return false;
  Writer& w = client_.beginRequest(kReadRequestId);
  encode(w, 0.0);  // MaxAge: the current value
  w.u32(kTimestampsNeither);
  w.i32(static_cast<int32_t>(2 * slots_.size()));
  for (const auto& node : nodeIds_) {
    for (uint32_t attribute : {kValueAttr, kUserAccessLevelAttr}) encodeReadValueId(w, node, attribute);
  }
  auto reply = client_.call(kReadResponseId);
  if (!reply) {
    problems.push_back({kNoSignal, "opcua: " + peerText() + " refused reading the wired nodes: " + reply.error().text, Problem::Kind::Link});
    return false;
  }
  uint32_t count = 0;
  if (!reply->arrayLength(count, 1) || count != 2 * slots_.size()) {
    problems.push_back({kNoSignal, "opcua: " + peerText() + " answered the Read of the wired nodes with " + std::to_string(count) +
                                       " results for " + std::to_string(2 * slots_.size()), Problem::Kind::Link});
    return false;
  }
  uint32_t imageBytes = 0;
  for (size_t i = 0; i < slots_.size(); ++i) {
    const BridgeSignal& s = config_.signals[i];
    Slot& slot = slots_[i];
    slot.found = slot.exists = false;
    RawValue value, access;
    if (!readRawValue(*reply, value)) {
      problems.push_back({kNoSignal, "opcua: " + peerText() + " sent a malformed Read response", Problem::Kind::Link});
      return false;
    }
    const bool unreadable = !value.wholly();  // an array or a non-elementary type: reported below
    if (!unreadable && !readRawValue(*reply, access)) {
      problems.push_back({kNoSignal, "opcua: " + peerText() + " sent a malformed Read response", Problem::Kind::Link});
      return false;
    }
    if (!unreadable && !access.wholly()) {
      problems.push_back({kNoSignal, "opcua: " + peerText() + " sent the UserAccessLevel of '" + s.node + "' as " +
                                         (access.isArray ? "an array of " : "") + builtinTypeName(access.type) + ", not a Byte",
                          Problem::Kind::Link});
      return false;
    }
    if (slot.unresolved) continue;
    const std::string wiredTo = s.port.empty() ? "" : " to wire to " + s.port;
    const std::string named = s.name == s.node ? "'" + s.node + "'" : "'" + s.name + "' (" + s.node + ")";
    if (value.status == static_cast<uint32_t>(StatusCodeValue::BadNodeIdUnknown)) {
      if (!s.optional) problems.push_back({i, "opcua: the server has no node " + named + wiredTo, Problem::Kind::Unknown});
      continue;
    }
    slot.exists = true;
    if (isBad(value.status)) {
      problems.push_back({i, "opcua: reading " + named + " failed: " + statusName(value.status)});
      continue;
    }
    auto type = elemTypeOfBuiltin(value.type);
    if (!type || value.isArray) {
      problems.push_back({i, "opcua: " + named + " is " + (value.isArray ? "an array of " : "") + builtinTypeName(value.type) +
                                 " on the server; only Boolean and numeric scalars can be wired"});
      // The rest of the response cannot be found past a value not read: stop here.
      return false;
    }
    const bool observedOnly = s.tag == kNoTag;
    if (observedOnly && addTags) {
      slot.tag = bus.find(s.name);
      if (slot.tag == kNoTag) slot.tag = bus.add(s.name, *type);
    }
    if (slot.tag == kNoTag) continue;
    const ElemType portType = bus.type(slot.tag);
    if (!observedOnly && !wireCompatible(portType, *type)) {
      const std::string expected(elemTypeInfo(portType).name);
      problems.push_back({i, "opcua: " + named + " is " + builtinTypeName(value.type) + " on the server but " +
                                 (s.port.empty() ? "must be " + expected : (s.toPlc ? "output '" : "input '") + s.port + "' is " + expected)});
      continue;
    }
    const bool writable = access.status == 0 && access.type == BuiltinType::Byte && (access.bytes[0] & kCurrentWrite);
    if (s.toPlc && !writable) {
      problems.push_back({i, "opcua: " + named + " is not writable for this session (UserAccessLevel) and cannot receive " + s.port +
                                 ": a read-only node, or a session without write access (virtcom: --opcua-anonymous write, or "
                                 "'user:' and 'password:' of a read-write user)"});
      continue;
    }
    if (!addTags && slot.wire != value.type) {
      problems.push_back({i, "opcua: " + named + " changed its type on the server to " + builtinTypeName(value.type)});
      continue;
    }
    slot.found = true;
    slot.wire = value.type;
    slot.type = *type;
    slot.size = static_cast<uint32_t>(value.bytes.size());
    slot.offset = imageBytes;
    slot.dirty = true;
    imageBytes += slot.size;
    (s.toPlc ? writes_ : reads_).push_back(i);
  }
  if (problems.size() != before) return false;
  image_.assign(imageBytes, 0);
  changed_.reserve(writes_.size());
  return true;
}

void ClientBridge::lose(const std::string& what) {
  client_.close();
  link_.lost(what);
}

bool ClientBridge::reconnect(TagBus& bus) {
  if (auto up = client_.connect(); !up) {
    if (up.error().linkLost) lose("cannot connect: " + up.error().text);
    else link_.refused("refused the session after reconnecting: " + up.error().text);
    return false;
  }
  std::vector<Problem> problems;
  resolve(bus, false, problems);
  if (!link_.recheckPassed(problems, [this] { client_.close(); })) return false;
  if (auto subscribed = subscribe(); !subscribed) {
    lose(subscribed.error());
    return false;
  }
  link_.reconnected();
  return true;
}

bool ClientBridge::pull(TagBus& bus, int64_t nowNs) {
  if (link_.failed()) return false;
  pollNow_ = nowNs >= nextPollNs_;
  if (!pollNow_) return true;
  nextPollNs_ = nowNs + config_.pollNs;
  if (!client_.connected() && !reconnect(bus)) return !link_.failed();
  if (reads_.empty()) return true;
  return subscribed() ? takePublished(bus) : readOutputs(bus);
}

bool ClientBridge::readOutputs(TagBus& bus) {
  Writer& w = client_.beginRequest(kReadRequestId);
  encode(w, 0.0);
  w.u32(kTimestampsNeither);
  w.i32(static_cast<int32_t>(reads_.size()));
  for (size_t i : reads_) encodeReadValueId(w, nodeIds_[i], kValueAttr);
  auto reply = client_.call(kReadResponseId);
  if (!reply) {
    if (reply.error().linkLost) lose("reading the PLC's outputs: " + reply.error().text);
    else link_.refused("refused the Read of its outputs: " + reply.error().text);
    return !link_.failed();
  }
  uint32_t count = 0;
  if (!reply->arrayLength(count, 1) || count != reads_.size()) {
    lose("a Read response with " + std::to_string(count) + " results for " + std::to_string(reads_.size()));
    return !link_.failed();
  }
  for (size_t i : reads_) {
    RawValue value;
    if (!readRawValue(*reply, value)) {
      lose("a malformed Read response");
      return !link_.failed();
    }
    if (!takeValue(bus, i, value)) return false;
  }
  return true;
}

bool ClientBridge::takeValue(TagBus& bus, size_t i, const RawValue& value) {
  const Slot& slot = slots_[i];
  if (isBad(value.status) || value.type != slot.wire || value.isArray) {
    link_.refused("refused reading '" + config_.signals[i].name + "': " +
                  (isBad(value.status) ? statusName(value.status) : std::string("its type changed to ") + builtinTypeName(value.type)));
    return false;
  }
  loadVariable(value.bytes.data(), -1, slot.type, bus, slot.tag);
  return true;
}

void ClientBridge::push(const TagBus& bus, int64_t) {
  if (!pollNow_ || link_.failed() || !client_.connected() || writes_.empty()) return;
  changed_.clear();
  for (size_t i : writes_) {
    Slot& slot = slots_[i];
    if (storeVariable(image_.data() + slot.offset, -1, slot.type, bus, slot.tag) || slot.dirty) changed_.push_back(i);
  }
  if (changed_.empty()) return;
  Writer& w = client_.beginRequest(kWriteRequestId);
  w.i32(static_cast<int32_t>(changed_.size()));
  for (size_t i : changed_) {
    const Slot& slot = slots_[i];
    encodeWriteValue(w, nodeIds_[i], slot.wire, {image_.data() + slot.offset, slot.size});
  }
  auto reply = client_.call(kWriteResponseId);
  if (!reply) {
    if (reply.error().linkLost) lose("writing the device outputs: " + reply.error().text);
    else link_.refused("refused the Write of the device outputs: " + reply.error().text);
    return;
  }
  uint32_t count = 0;
  if (!reply->arrayLength(count, 4) || count != changed_.size()) {
    lose("a Write response with " + std::to_string(count) + " results for " + std::to_string(changed_.size()));
    return;
  }
  for (size_t i : changed_) {
    uint32_t status = 0;
    if (!reply->u32(status)) {
      lose("a malformed Write response");
      return;
    }
    if (isBad(status)) {
      link_.refused("refused writing '" + config_.signals[i].name + "': " + statusName(status));
      return;
    }
  }
  for (size_t i : changed_) slots_[i].dirty = false;
}

void ClientBridge::simulationStopped() {
  if (config_.disconnectWhenStopped) client_.close();
}

}  // namespace virtcom::proto::opcua

#include "proto/ads/client_bridge.hpp"

#include <algorithm>

#include "core/value_codec.hpp"
#include "proto/ads/byte_io.hpp"
#include "proto/ads/entries.hpp"
#include "proto/ads/index_group.hpp"

namespace virtcom::proto::ads {

namespace {

constexpr uint32_t kIgSumRead = static_cast<uint32_t>(IndexGroup::SumRead);
constexpr uint32_t kIgSumWrite = static_cast<uint32_t>(IndexGroup::SumWrite);
constexpr uint32_t kIgValueByHandle = static_cast<uint32_t>(IndexGroup::SymValueByHandle);
constexpr uint32_t kIgHandleByName = static_cast<uint32_t>(IndexGroup::SymHandleByName);
constexpr uint32_t kIgReleaseHandle = static_cast<uint32_t>(IndexGroup::SymReleaseHandle);
constexpr uint32_t kIgInfoByNameEx = static_cast<uint32_t>(IndexGroup::SymInfoByNameEx);

// The elementary type a symbol is stored as: its IEC type name when that is one of the
// elementary types at the symbol's size, else (enums, aliases) by its ADS type id. Nullopt for
// structs, arrays, strings.
std::optional<ElemType> storageType(const Symbol& s, bool& isEnum) {
  isEnum = false;
  ElemType byName;
  if (elemTypeByName(s.type, byName) && elemTypeInfo(byName).kind != ElemKind::Text) return byName;
  isEnum = s.adsType != adst::kBit;
  switch (s.adsType) {
    case adst::kBit: return ElemType::Bool;
    case adst::kInt8: return ElemType::Sint;
    case adst::kUint8: return ElemType::Usint;
    case adst::kInt16: return ElemType::Int;
    case adst::kUint16: return ElemType::Uint;
    case adst::kInt32: return ElemType::Dint;
    case adst::kUint32: return ElemType::Udint;
    case adst::kInt64: return ElemType::Lint;
    case adst::kUint64: return ElemType::Ulint;
    case adst::kReal32: return ElemType::Real;
    case adst::kReal64: return ElemType::Lreal;
    default: return std::nullopt;
  }
}

std::vector<uint8_t> nameBytes(const std::string& name) {
  std::vector<uint8_t> b(name.begin(), name.end());
  b.push_back(0);  // TwinCAT takes names with or without the NUL (docs/ads.md, Symbol services)
  return b;
}

}  // namespace

ClientBridge::ClientBridge(BridgeConfig config)
    : config_(std::move(config)),
      client_(config_.client),
      link_({"ads", peerText(), "every step", config_.faultOnLoss, config_.report}) {
  slots_.resize(config_.signals.size());
  for (size_t i = 0; i < slots_.size(); ++i) slots_[i].tag = config_.signals[i].tag;
}

ClientBridge::~ClientBridge() = default;

std::string ClientBridge::peerText() const {
  const ClientConfig& c = config_.client;
  return "the PLC at " + net::formatEndpoint(c.router) + " (AmsNetId " + formatNetId(c.target.netId) + ", port " +
         std::to_string(c.target.port) + ")";
}

std::unique_ptr<ClientBridge> ClientBridge::start(BridgeConfig config, TagBus& bus, StartReport& report) {
  std::unique_ptr<ClientBridge> b(new ClientBridge(std::move(config)));
  report.found.assign(b->slots_.size(), false);
  if (auto up = b->client_.connect(); !up) {
    report.problems.push_back({kNoSignal, "ads: cannot connect to " + b->peerText() + ": " + up.error().text, Problem::Kind::Link});
    return nullptr;
  }
  bool ok = b->resolve(bus, true, report.problems);
  for (size_t i = 0; i < b->slots_.size(); ++i) report.found[i] = b->slots_[i].exists;
  if (!ok) return nullptr;
  return b;
}

// The {IG, IO, length} header of a sum read or write (docs/ads.md, Sum commands) for each slot, by handle.
void ClientBridge::writeSumHeaders(LittleEndianWriter& w, const std::vector<size_t>& slots) const {
  for (size_t i : slots) {
    w.u32(kIgValueByHandle);
    w.u32(slots_[i].handle);
    w.u32(slots_[i].size);
  }
}

bool ClientBridge::resolve(TagBus& bus, bool addTags, std::vector<Problem>& problems) {
  const size_t before = problems.size();
  reads_.clear();
  writes_.clear();
  uint32_t imageBytes = 0, readBytes = 0, writeBytes = 0;
  for (size_t i = 0; i < config_.signals.size(); ++i) {
    const BridgeSignal& s = config_.signals[i];
    Slot& slot = slots_[i];
    slot.found = slot.exists = false;
    const std::vector<uint8_t> name = nameBytes(s.variable);
    const std::string wiredTo = s.port.empty() ? "" : " to wire to " + s.port;
    auto info = client_.readWrite(kIgInfoByNameEx, 0, kAnyLength, name);
    if (!info) {
      if (info.error().linkLost) {
        problems.push_back({kNoSignal, "ads: link to " + peerText() + " lost: " + info.error().text, Problem::Kind::Link});
        return false;
      }
      if (info.error().code < 0x700) {
        // An AMS or router error (docs/ads.md, AMS/TCP and the AMS header): the target itself is
        // wrong, not this variable.
        problems.push_back({kNoSignal, "ads: " + peerText() + " refused the first request: " + info.error().text +
                                           " (check 'netid' and 'port')", Problem::Kind::Link});
        return false;
      }
      if (info.error().code == static_cast<uint32_t>(AdsError::SymbolNotFound)) {
        if (!s.optional) problems.push_back({i, "ads: the PLC has no variable '" + s.variable + "'" + wiredTo, Problem::Kind::Unknown});
      } else {
        problems.push_back({i, "ads: looking up '" + s.variable + "' failed: " + info.error().text});
      }
      continue;
    }
    slot.exists = true;
    auto symbol = parseSymbolEntry(*info);
    if (!symbol) {
      problems.push_back({i, "ads: the PLC's symbol entry of '" + s.variable + "' is malformed"});
      continue;
    }
    bool isEnum = false;
    auto type = storageType(*symbol, isEnum);
    if (!type) {
      problems.push_back({i, "ads: '" + s.variable + "' is a " + symbol->type + " on the PLC; only BOOL, numeric and enum "
                                                                    "variables can be wired"});
      continue;
    }
    if (symbol->size != elemTypeInfo(*type).sizeBytes) {
      problems.push_back({i, "ads: '" + s.variable + "' is " + symbol->type + " of " + std::to_string(symbol->size) +
                                 " bytes on the PLC, expected " + std::to_string(elemTypeInfo(*type).sizeBytes)});
      continue;
    }
    const bool observedOnly = s.tag == kNoTag;
    if (observedOnly && addTags) {
      slot.tag = bus.find(s.variable);
      if (slot.tag == kNoTag) slot.tag = bus.add(s.variable, *type);
    }
    if (slot.tag == kNoTag) continue;  // reconnecting after a failed start: cannot happen
    const ElemType portType = bus.type(slot.tag);
    if (!observedOnly && !wireCompatible(portType, *type, isEnum)) {
      const std::string expected(elemTypeInfo(portType).name);
      problems.push_back({i, "ads: '" + s.variable + "' is " + symbol->type + " on the PLC but " +
                                 (s.port.empty() ? "must be " + expected
                                                 : (s.toPlc ? "output '" : "input '") + s.port + "' is " + expected)});
      continue;
    }
    if (s.toPlc && (symbol->flags & kSymbolFlagReadOnly)) {
      problems.push_back({i, "ads: '" + s.variable + "' is read-only on the PLC and cannot receive " + s.port});
      continue;
    }
    auto handle = client_.readWrite(kIgHandleByName, 0, 4, name);
    if (!handle) {
      if (handle.error().linkLost) {
        problems.push_back({kNoSignal, "ads: link to " + peerText() + " lost: " + handle.error().text, Problem::Kind::Link});
        return false;
      }
      problems.push_back({i, "ads: no handle for '" + s.variable + "': " + handle.error().text});
      continue;
    }
    auto h = LittleEndianReader(*handle).u32();
    if (!h || handle->size() != 4) {
      problems.push_back({i, "ads: the handle reply for '" + s.variable + "' is not 4 bytes"});
      continue;
    }
    if (!addTags && slot.type != *type) {
      problems.push_back({i, "ads: '" + s.variable + "' changed its type on the PLC to " + symbol->type});
      continue;
    }
    slot.found = true;
    slot.type = *type;
    slot.size = symbol->size;
    slot.handle = *h;
    slot.offset = imageBytes;
    slot.dirty = true;
    imageBytes += slot.size;
    (s.toPlc ? writes_ : reads_).push_back(i);
    (s.toPlc ? writeBytes : readBytes) += slot.size;
  }
  if (problems.size() != before) return false;
  image_.assign(imageBytes, 0);
  readRequest_.clear();
  LittleEndianWriter w(readRequest_);
  writeSumHeaders(w, reads_);
  writeRequest_.reserve(12 * writes_.size() + writeBytes);
  changed_.reserve(writes_.size());
  client_.reserve(16 + std::max(readRequest_.size(), writeRequest_.capacity()), 8 + 4 * reads_.size() + readBytes + 4 * writes_.size());
  return true;
}

void ClientBridge::lose(const std::string& what) {
  client_.close();
  link_.lost(what);
}

bool ClientBridge::reconnect(TagBus& bus) {
  if (auto up = client_.connect(); !up) {
    lose("cannot connect: " + up.error().text);
    return false;
  }
  std::vector<Problem> problems;
  resolve(bus, false, problems);
  if (!link_.recheckPassed(problems, [this] { client_.close(); })) return false;
  link_.reconnected();
  return true;
}

bool ClientBridge::pull(TagBus& bus, int64_t) {
  if (link_.failed()) return false;
  if (!client_.connected() && !reconnect(bus)) return !link_.failed();
  if (reads_.empty()) return true;
  const uint32_t n = static_cast<uint32_t>(reads_.size());
  const uint32_t length = static_cast<uint32_t>(4 * n + image_.size());  // an upper bound: results + read data
  auto reply = client_.readWrite(kIgSumRead, n, length, readRequest_);
  if (!reply) {
    if (reply.error().linkLost) lose("reading the PLC's outputs: " + reply.error().text);
    else link_.refused("refused the sum read of its outputs: " + reply.error().text);
    return !link_.failed();
  }
  // Reply: n results, then each item's data at its requested length (docs/ads.md, Sum commands).
  size_t at = 4 * n;
  for (uint32_t k = 0; k < n; ++k) {
    const Slot& slot = slots_[reads_[k]];
    const uint32_t result = LittleEndianReader(reply->subspan(4 * k)).u32().value_or(0);
    if (result != 0 || at + slot.size > reply->size()) {
      link_.refused("refused reading '" + config_.signals[reads_[k]].variable + "': " +
           (result ? adsErrorText(result) : std::string("short sum read reply")));
      return false;
    }
    loadVariable(reply->data() + at, -1, slot.type, bus, slot.tag);
    at += slot.size;
  }
  return true;
}

void ClientBridge::push(const TagBus& bus, int64_t) {
  if (link_.failed() || !client_.connected() || writes_.empty()) return;
  changed_.clear();
  for (size_t i : writes_) {
    Slot& slot = slots_[i];
    if (storeVariable(image_.data() + slot.offset, -1, slot.type, bus, slot.tag) || slot.dirty) changed_.push_back(i);
  }
  if (changed_.empty()) return;
  if (changed_.size() == 1) {
    const Slot& slot = slots_[changed_[0]];
    auto done = client_.write(kIgValueByHandle, slot.handle, {image_.data() + slot.offset, slot.size});
    if (!done) {
      if (done.error().linkLost) lose("writing '" + config_.signals[changed_[0]].variable + "': " + done.error().text);
      else link_.refused("refused writing '" + config_.signals[changed_[0]].variable + "': " + done.error().text);
      return;
    }
  } else {
    // Sum write (docs/ads.md, Sum commands): n x {IG, IO, length}, then all the data; reply: n results.
    writeRequest_.clear();
    LittleEndianWriter w(writeRequest_);
    writeSumHeaders(w, changed_);
    for (size_t i : changed_) w.bytes({image_.data() + slots_[i].offset, slots_[i].size});
    const uint32_t n = static_cast<uint32_t>(changed_.size());
    auto reply = client_.readWrite(kIgSumWrite, n, 4 * n, writeRequest_);
    if (!reply) {
      if (reply.error().linkLost) lose("writing the device outputs: " + reply.error().text);
      else link_.refused("refused the sum write of the device outputs: " + reply.error().text);
      return;
    }
    for (uint32_t k = 0; k < n; ++k) {
      const uint32_t result = reply->size() >= 4 * n ? LittleEndianReader(reply->subspan(4 * k)).u32().value_or(0) : 1;
      if (result != 0) {
        link_.refused("refused writing '" + config_.signals[changed_[k]].variable + "': " + adsErrorText(result));
        return;
      }
    }
  }
  for (size_t i : changed_) slots_[i].dirty = false;
}

void ClientBridge::releaseHandles() {
  // As ads-client's deleteVariableHandleMulti: a sum write of 0xF006 items of 4 bytes each.
  std::vector<uint8_t> request;
  LittleEndianWriter w(request);
  uint32_t n = 0;
  for (const Slot& slot : slots_)
    if (slot.found) {
      w.u32(kIgReleaseHandle);
      w.u32(0);
      w.u32(4);
      ++n;
    }
  for (const Slot& slot : slots_)
    if (slot.found) w.u32(slot.handle);
  if (n > 0) (void)client_.readWrite(kIgSumWrite, n, 4 * n, request);
  for (Slot& slot : slots_) slot.found = false;
}

void ClientBridge::simulationStopped() {
  if (!config_.disconnectWhenStopped || !client_.connected()) return;
  releaseHandles();
  client_.close();
}

}  // namespace virtcom::proto::ads

#include "proto/opcua/server_core.hpp"

#include <algorithm>
#include <random>

#include "core/clock.hpp"

namespace virtcom::proto::opcua {

namespace {

// DateTime ticks (100 ns since 1601) of the Unix epoch (OPC 10000-6 §5.2.2.5).
constexpr int64_t kUnixEpochTicks = 116'444'736'000'000'000;

}  // namespace

bool ServerCore::offers(SecurityMode mode) const {
  return std::ranges::find(config_.securityModes, mode) != config_.securityModes.end();
}

DateTime dateTimeNow() { return DateTime{kUnixEpochTicks + utcNowNs() / 100}; }

ServerCore::ServerCore(const ads::SymbolTable& table, ServerConfig config)
    : config_(std::move(config)),
      space_(table, config_.names),
      snapshot_(table.layout().dataSize + config_.names.extraBytes, 0),
      pending_(config_.writeQueueBytes),
      startTime_(dateTimeNow()) {
  // Authentication tokens must not be guessable from the session ids clients see.
  tokenSalt_ = std::random_device{}();
}

std::string ServerCore::endpointUrl() const {
  return config_.endpointUrl.empty() ? "opc.tcp://" + formatEndpoint(config_.listen) : config_.endpointUrl;
}

uint32_t ServerCore::write(const PlcValue& v, std::span<const uint8_t> bytes) {
  if (!pending_.hasRoom(bytes.size())) return static_cast<uint32_t>(StatusCodeValue::BadTooManyOperations);
  if (v.bit >= 0) {
    const auto mask = static_cast<uint8_t>(1u << v.bit);
    pending_.push(v.offset, bytes.first(1), mask);
    uint8_t& b = snapshot_[v.offset];
    b = static_cast<uint8_t>(bytes[0] ? b | mask : b & ~mask);
    return 0;
  }
  pending_.push(v.offset, bytes);
  std::copy(bytes.begin(), bytes.end(), snapshot_.begin() + v.offset);
  return 0;
}

void ServerCore::publish(std::span<const uint8_t> image, std::span<const uint8_t> extra) {
  const size_t dataSize = snapshot_.size() - config_.names.extraBytes;
  std::copy_n(image.begin(), std::min(image.size(), dataSize), snapshot_.begin());
  std::copy_n(extra.begin(), std::min<size_t>(extra.size(), config_.names.extraBytes), snapshot_.begin() + static_cast<std::ptrdiff_t>(dataSize));
  // Writes not yet taken by the scan stay visible, so a client reads back what it wrote.
  pending_.applyTo(snapshot_);
}

Session* ServerCore::createSession(uint32_t channelId, double timeoutMs, std::string name, int64_t nowNs) {
  std::erase_if(sessions_, [nowNs](const Session& s) { return nowNs - s.lastUsedNs > static_cast<int64_t>(s.timeoutMs * 1e6); });
  if (sessions_.size() >= config_.maxSessions) return nullptr;
  Session s;
  s.id = nextSessionId_++;
  s.token = (s.id * 2654435761u) ^ tokenSalt_;
  s.channelId = channelId;
  s.timeoutMs = timeoutMs;
  s.lastUsedNs = nowNs;
  s.name = std::move(name);
  sessions_.push_back(std::move(s));
  return &sessions_.back();
}

Session* ServerCore::findSession(const NodeId& token) {
  if (token.ns != 1 || token.kind != NodeId::Kind::Numeric) return nullptr;
  auto it = std::find_if(sessions_.begin(), sessions_.end(), [&](const Session& s) { return s.token == token.numeric; });
  return it == sessions_.end() ? nullptr : &*it;
}

void ServerCore::closeSession(uint32_t id) {
  std::erase_if(sessions_, [id](const Session& s) { return s.id == id; });
}

}  // namespace virtcom::proto::opcua

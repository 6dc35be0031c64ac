#include "proto/opcua/transport.hpp"

#include <cstring>

namespace virtcom::proto::opcua {

namespace {

// The longest endpoint URL a Hello may carry (OPC 10000-6 §7.1.2.3).
constexpr size_t kMaxEndpointUrl = 4096;

}  // namespace

MessageType messageTypeOf(std::span<const uint8_t> header) {
  if (header.size() < 3) return MessageType::Unknown;
  struct Name {
    const char* text;
    MessageType type;
  };
  for (const Name& n : {Name{"HEL", MessageType::Hello}, Name{"ACK", MessageType::Acknowledge}, Name{"ERR", MessageType::Error},
                        Name{"RHE", MessageType::ReverseHello}, Name{"OPN", MessageType::Open},
                        Name{"MSG", MessageType::Message}, Name{"CLO", MessageType::Close}})
    if (std::memcmp(header.data(), n.text, 3) == 0) return n.type;
  return MessageType::Unknown;
}

FrameScan scanFrame(std::span<const uint8_t> stream, size_t maxBytes) {
  if (stream.size() < kMessageHeaderSize) return {};
  const uint32_t size = stream[4] | (uint32_t{stream[5]} << 8) | (uint32_t{stream[6]} << 16) | (uint32_t{stream[7]} << 24);
  if (size < kMessageHeaderSize || size > maxBytes) return {FrameStatus::Malformed, 0};
  if (stream.size() < size) return {};
  return {FrameStatus::Complete, size};
}

bool decodeHello(std::span<const uint8_t> body, Hello& out) {
  Reader r(body);
  if (!r.u32(out.protocolVersion) || !r.u32(out.receiveBufferSize) || !r.u32(out.sendBufferSize) ||
      !r.u32(out.maxMessageSize) || !r.u32(out.maxChunkCount))
    return false;
  return decode(r, out.endpointUrl) && out.endpointUrl.size() <= kMaxEndpointUrl;
}

size_t beginMessage(Writer& w, std::string_view type, char chunk) {
  const size_t start = w.size();
  for (char c : type) w.u8(static_cast<uint8_t>(c));
  w.u8(static_cast<uint8_t>(chunk));
  w.u32(0);
  return start;
}

void finishMessage(Writer& w, size_t start) { w.put32(start + 4, static_cast<uint32_t>(w.size() - start)); }

void writeError(Writer& w, uint32_t status, std::string_view reason) {
  const size_t start = beginMessage(w, "ERR");
  w.u32(status);
  w.string(reason);
  finishMessage(w, start);
}

}  // namespace virtcom::proto::opcua

#pragma once
// OPC UA Connection Protocol framing (docs/opcua.md, Wire reference: Messages; OPC 10000-6
// §7.1.2): every message starts with a 3-byte type, a chunk type ('F' final, 'C' intermediate,
// 'A' abort) and a uint32 size that counts the 8-byte header.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "proto/opcua/binary_codec.hpp"

namespace virtcom::proto::opcua {

inline constexpr size_t kMessageHeaderSize = 8;
// The smallest buffer a peer may announce (OPC 10000-6 §7.1.2.3).
inline constexpr uint32_t kMinBufferSize = 8192;
inline constexpr uint32_t kProtocolVersion = 0;

enum class MessageType : uint8_t { Hello, Acknowledge, Error, ReverseHello, Open, Message, Close, Unknown };
// "HEL" -> Hello ...; Unknown for anything else.
MessageType messageTypeOf(std::span<const uint8_t> header);

enum class FrameStatus : uint8_t { NeedMore, Complete, Malformed };
struct FrameScan {
  FrameStatus status = FrameStatus::NeedMore;
  size_t size = 0;
};
// Looks at the start of a receive stream: a whole message of `size` bytes, more needed, or a
// size below the header or above `maxBytes` (the connection is answered with ERR and closed).
FrameScan scanFrame(std::span<const uint8_t> stream, size_t maxBytes);

struct Hello {
  uint32_t protocolVersion = 0, receiveBufferSize = 0, sendBufferSize = 0, maxMessageSize = 0, maxChunkCount = 0;
  std::string endpointUrl;
};
// The body of a HEL message (after the header). False if short or the URL is over 4096 bytes.
bool decodeHello(std::span<const uint8_t> body, Hello& out);

// Starts a message of `type` ("ACK", "OPN", ...) and `chunk`; finishMessage patches its size.
size_t beginMessage(Writer& w, std::string_view type, char chunk = 'F');
void finishMessage(Writer& w, size_t start);
// A whole ERR message: the status code and a reason for humans.
void writeError(Writer& w, uint32_t status, std::string_view reason);

}  // namespace virtcom::proto::opcua

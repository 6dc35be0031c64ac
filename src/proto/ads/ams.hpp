#pragma once
// AMS/TCP framing and the AMS header (docs/ads.md, Wire reference: AMS/TCP and the
// AMS header), as pure functions over spans:
// no sockets, no threads; scanFrame never reads past its buffer.
//   AMS/TCP header (6 bytes): u16 command (0 = AMS packet, 0x1000 port connect, ...), u32 length
//   AMS header (32 bytes): target NetId(6) + port u16, source NetId(6) + port u16, u16 command id,
//                          u16 state flags, u32 data length, u32 error code, u32 invoke id
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/ams_net_id.hpp"

namespace virtcom::proto::ads {

inline constexpr size_t kAmsTcpHeaderSize = 6;
inline constexpr size_t kAmsHeaderSize = 32;
inline constexpr size_t kFrameHeaderSize = kAmsTcpHeaderSize + kAmsHeaderSize;

enum class AmsTcpCommand : uint16_t {
  AmsPacket = 0x0000,
  PortClose = 0x0001,
  PortConnect = 0x1000,
  RouterNote = 0x1001,
  GetLocalNetId = 0x1002,
};

enum class Command : uint16_t {
#define ADS_COMMAND(name, id, requestBytes, errorReplyBytes) name = id,
#include "proto/ads/commands.def"
#undef ADS_COMMAND
};
// True for ids 1..9.
bool isKnownCommand(uint16_t id);
// The fixed request size and the error-only reply size of a known command (commands.def).
size_t requestBytes(Command c);
size_t errorReplyBytes(Command c);

enum class AdsError : uint32_t {
#define ADS_ERROR(name, code, text) name = code,
#include "proto/ads/errors.def"
#undef ADS_ERROR
};
// The spec's text of a code the server sends, or "ADS error" for others.
const char* errorText(uint32_t code);

namespace state_flags {
inline constexpr uint16_t kResponse = 0x0005;      // response | ADS command (ads-rs requires exactly 5)
inline constexpr uint16_t kNotification = 0x0004;  // ADS command, no response bit
}  // namespace state_flags

// The AmsNetId text is core's (the cell file names AmsNetIds too); named here for ADS.
using virtcom::AmsNetId;
using virtcom::formatNetId;
using virtcom::kLocalAliasNetId;
using virtcom::parseNetId;

struct AmsAddress {
  AmsNetId netId{};
  uint16_t port = 0;
  bool operator==(const AmsAddress&) const = default;
};

struct AmsHeader {
  AmsAddress target, source;
  uint16_t commandId = 0;
  uint16_t stateFlags = 0;
  uint32_t dataLength = 0;
  uint32_t errorCode = 0;
  uint32_t invokeId = 0;
};

enum class FrameStatus {
  NeedMore,   // not a whole frame yet
  Complete,   // the first `size` bytes are one frame
  Malformed,  // AMS/TCP length above the limit, an AMS packet shorter than its header, or a data
              // length that disagrees with the AMS/TCP length: close the connection
};

struct FrameScan {
  FrameStatus status = FrameStatus::NeedMore;
  size_t size = 0;           // whole frame, AMS/TCP header included
  uint16_t tcpCommand = 0;   // AmsTcpCommand
};

// Looks at the start of a receive buffer. `maxFrameBytes` bounds the AMS/TCP length so a peer
// cannot make the server buffer without limit. Allocates nothing.
FrameScan scanFrame(std::span<const uint8_t> buffer, size_t maxFrameBytes);

// The AMS header of a complete AMS packet frame (as found by scanFrame), or nullopt if the
// frame is too short. The ADS data are frame.subspan(kFrameHeaderSize).
std::optional<AmsHeader> readAmsHeader(std::span<const uint8_t> frame);

// Appends the AMS/TCP and AMS headers of a packet with `dataLength` bytes of ADS data.
void writeAmsFrameHeader(std::vector<uint8_t>& out, const AmsHeader& h);
// The header of the response to `request`: addresses swapped verbatim, flags 0x0005, the same
// command and invoke id, the given error code and data length.
AmsHeader responseHeader(const AmsHeader& request, uint32_t dataLength, uint32_t errorCode = 0);

}  // namespace virtcom::proto::ads

#include "proto/ads/ams.hpp"

#include "proto/ads/byte_io.hpp"

namespace virtcom::proto::ads {

namespace {

struct CommandRow {
  size_t requestBytes;
  size_t errorReplyBytes;
};

constexpr CommandRow kCommandRows[] = {
    {0, 0},
#define ADS_COMMAND(name, id, requestBytes, errorReplyBytes) {requestBytes, errorReplyBytes},
#include "proto/ads/commands.def"
#undef ADS_COMMAND
};

void writeAddress(LittleEndianWriter& w, const AmsAddress& a) {
  w.bytes(a.netId);
  w.u16(a.port);
}

std::optional<AmsAddress> readAddress(LittleEndianReader& in) {
  auto id = in.bytes(6);
  auto port = in.u16();
  if (!id || !port) return std::nullopt;
  AmsAddress a;
  std::copy(id->begin(), id->end(), a.netId.begin());
  a.port = *port;
  return a;
}

}  // namespace

bool isKnownCommand(uint16_t id) { return id >= 1 && id < std::size(kCommandRows); }
size_t requestBytes(Command c) { return kCommandRows[static_cast<uint16_t>(c)].requestBytes; }
size_t errorReplyBytes(Command c) { return kCommandRows[static_cast<uint16_t>(c)].errorReplyBytes; }

const char* errorText(uint32_t code) {
  switch (code) {
#define ADS_ERROR(name, value, text) \
  case value: return text;
#include "proto/ads/errors.def"
#undef ADS_ERROR
  }
  return "ADS error";
}

FrameScan scanFrame(std::span<const uint8_t> buffer, size_t maxFrameBytes) {
  LittleEndianReader in(buffer);
  auto command = in.u16();
  auto length = in.u32();
  if (!command || !length) return {};
  if (*length > maxFrameBytes) return {FrameStatus::Malformed, 0, *command};
  const size_t total = kAmsTcpHeaderSize + *length;
  if (*command == static_cast<uint16_t>(AmsTcpCommand::AmsPacket)) {
    if (*length < kAmsHeaderSize) return {FrameStatus::Malformed, 0, *command};
    if (buffer.size() >= kAmsTcpHeaderSize + 24) {
      // AMS data length (offset 20 of the AMS header) must be the AMS/TCP length - 32.
      LittleEndianReader data(buffer.subspan(kAmsTcpHeaderSize + 20, 4));
      if (*data.u32() != *length - kAmsHeaderSize) return {FrameStatus::Malformed, 0, *command};
    }
  }
  if (buffer.size() < total) return {FrameStatus::NeedMore, 0, *command};
  return {FrameStatus::Complete, total, *command};
}

std::optional<AmsHeader> readAmsHeader(std::span<const uint8_t> frame) {
  if (frame.size() < kFrameHeaderSize) return std::nullopt;
  LittleEndianReader in(frame.subspan(kAmsTcpHeaderSize));
  AmsHeader h;
  auto target = readAddress(in), source = readAddress(in);
  auto command = in.u16(), flags = in.u16();
  auto length = in.u32(), error = in.u32(), invoke = in.u32();
  if (!target || !source || !command || !flags || !length || !error || !invoke) return std::nullopt;
  h.target = *target;
  h.source = *source;
  h.commandId = *command;
  h.stateFlags = *flags;
  h.dataLength = *length;
  h.errorCode = *error;
  h.invokeId = *invoke;
  return h;
}

void writeAmsFrameHeader(std::vector<uint8_t>& out, const AmsHeader& h) {
  LittleEndianWriter w(out);
  w.u16(static_cast<uint16_t>(AmsTcpCommand::AmsPacket));
  w.u32(static_cast<uint32_t>(kAmsHeaderSize + h.dataLength));
  writeAddress(w, h.target);
  writeAddress(w, h.source);
  w.u16(h.commandId);
  w.u16(h.stateFlags);
  w.u32(h.dataLength);
  w.u32(h.errorCode);
  w.u32(h.invokeId);
}

AmsHeader responseHeader(const AmsHeader& request, uint32_t dataLength, uint32_t errorCode) {
  AmsHeader h;
  h.target = request.source;
  h.source = request.target;
  h.commandId = request.commandId;
  h.stateFlags = state_flags::kResponse;
  h.dataLength = dataLength;
  h.errorCode = errorCode;
  h.invokeId = request.invokeId;
  return h;
}

}  // namespace virtcom::proto::ads

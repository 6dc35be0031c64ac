// Session: frame dispatch and the nine ADS commands (docs/ads.md, Wire reference: AMS/TCP
// and the AMS header, Commands).
#include "proto/ads/session.hpp"

#include <algorithm>
#include <cstring>

#include "proto/ads/byte_io.hpp"
#include "proto/ads/index_group.hpp"

namespace virtcom::proto::ads {

namespace {

// TwinCAT 3.1.4024 as ads-client's tests pin it (docs/ads.md, Commands); names per AMS port.
constexpr uint8_t kVersionMajor = 3, kVersionMinor = 1;
constexpr uint16_t kVersionBuild = 4024;
// Port 10000's deviceState on a real TC3 (docs/ads.md, States and return codes).
constexpr uint16_t kSystemDeviceState = 1;

void appendDeviceInfo(std::vector<uint8_t>& reply, const char* name) {
  LittleEndianWriter w(reply);
  w.u8(kVersionMajor);
  w.u8(kVersionMinor);
  w.u16(kVersionBuild);
  char padded[16] = {};
  std::strncpy(padded, name, sizeof padded - 1);
  w.bytes(std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(padded), sizeof padded));
}

}  // namespace

Session::Session(Device& device, std::vector<AmsNetId> allowedNetIds)
    : device_(device), allowedNetIds_(std::move(allowedNetIds)) {}

void Session::end() {
  if (registered_) device_.handles().releaseRoute(*registered_);
  registered_.reset();
}

bool Session::handleFrame(std::span<const uint8_t> frame, std::vector<uint8_t>& out, bool withinRate) {
  LittleEndianReader in(frame);
  const auto tcpCommand = static_cast<AmsTcpCommand>(in.u16().value_or(0xFFFF));
  in.u32();
  switch (tcpCommand) {
    case AmsTcpCommand::AmsPacket: break;
    case AmsTcpCommand::PortConnect: {
      // Reply: this router's NetId and the client's port (docs/ads.md, AMS/TCP and the AMS
      // header); 0 asks for any port.
      const uint16_t requested = in.u16().value_or(0);
      registered_ = AmsAddress{device_.config().netId, requested ? requested : device_.assignPort()};
      LittleEndianWriter w(out);
      w.u16(static_cast<uint16_t>(AmsTcpCommand::PortConnect));
      w.u32(8);
      w.bytes(registered_->netId);
      w.u16(registered_->port);
      return true;
    }
    case AmsTcpCommand::PortClose: return false;
    default: return true;  // router notes and NetId queries from a client carry nothing to answer
  }
  auto header = readAmsHeader(frame);
  if (!header) return false;
  if (!allowedNetIds_.empty() &&
      std::find(allowedNetIds_.begin(), allowedNetIds_.end(), header->source.netId) == allowedNetIds_.end())
    return false;
  if (header->stateFlags & 0x0001) return true;  // a response from the client: nothing to answer
  answerPacket(*header, frame.subspan(kFrameHeaderSize), out, withinRate);
  return true;
}

void Session::answerPacket(const AmsHeader& h, std::span<const uint8_t> data, std::vector<uint8_t>& out, bool withinRate) {
  // AMS-level errors (docs/ads.md, AMS/TCP and the AMS header): no ADS data, the code in the header.
  auto amsError = [&](AdsError e) { writeAmsFrameHeader(out, responseHeader(h, 0, static_cast<uint32_t>(e))); };
  if (h.target.netId != device_.config().netId && h.target.netId != kLocalAliasNetId)
    return amsError(AdsError::TargetMachineNotFound);
  if (h.target.port != kPlcPort && h.target.port != kSystemPort) return amsError(AdsError::TargetPortNotFound);
  if (!isKnownCommand(h.commandId) || h.commandId == static_cast<uint16_t>(Command::DeviceNotification))
    return amsError(AdsError::UnknownCommandId);
  const auto command = static_cast<Command>(h.commandId);
  currentClient_ = h.source;
  currentServer_ = h.target;
  writer_.hasNetId = true;
  writer_.netId = h.source.netId;
  device_.pendingWrites().setWriter(writer_);
  reply_.clear();
  LittleEndianWriter(reply_).u32(0);  // result, patched below
  AdsError result = !withinRate                          ? AdsError::DeviceBusy
                    : data.size() < requestBytes(command) ? AdsError::InvalidSize
                    : h.target.port == kPlcPort        ? plcCommand(h, data)
                                                       : systemCommand(h, data);
  if (result != AdsError::None) {
    // Clients parse the fixed layout even on error (docs/ads.md, Commands): result, then zeros.
    reply_.assign(errorReplyBytes(command), 0);
    LittleEndianWriter(reply_).put32(0, static_cast<uint32_t>(result));
  }
  writeAmsFrameHeader(out, responseHeader(h, static_cast<uint32_t>(reply_.size())));
  out.insert(out.end(), reply_.begin(), reply_.end());
}

AdsError Session::plcCommand(const AmsHeader& h, std::span<const uint8_t> data) {
  LittleEndianReader in(data);
  LittleEndianWriter w(reply_);
  switch (static_cast<Command>(h.commandId)) {
    case Command::ReadDeviceInfo: appendDeviceInfo(reply_, "Plc30 App"); return AdsError::None;
    case Command::Read: {
      const uint32_t ig = *in.u32(), io = *in.u32(), length = *in.u32();
      w.u32(0);  // length, patched
      AdsError e = read(ig, io, length, reply_);
      w.put32(4, static_cast<uint32_t>(reply_.size() - 8));
      return e;
    }
    case Command::Write: {
      const uint32_t ig = *in.u32(), io = *in.u32(), length = *in.u32();
      auto payload = in.bytes(length);
      return payload ? write(ig, io, *payload) : AdsError::InvalidSize;
    }
    case Command::ReadState:
      w.u16(device_.adsState());
      w.u16(0);
      return AdsError::None;
    case Command::WriteControl: return device_.requestState(*in.u16(), writer_);
    case Command::AddDeviceNotification: {
      uint32_t handle = 0;
      AdsError e = addNotification(data.first(40), handle);
      w.u32(handle);
      return e;
    }
    case Command::DeleteDeviceNotification: return deleteNotification(*in.u32());
    case Command::ReadWrite: {
      const uint32_t ig = *in.u32(), io = *in.u32(), readLength = *in.u32(), writeLength = *in.u32();
      auto payload = in.bytes(writeLength);
      if (!payload) return AdsError::InvalidSize;
      w.u32(0);
      AdsError e = readWrite(ig, io, readLength, *payload, reply_, false);
      w.put32(4, static_cast<uint32_t>(reply_.size() - 8));
      return e;
    }
    case Command::DeviceNotification: break;
  }
  return AdsError::ServiceNotSupported;
}

AdsError Session::systemCommand(const AmsHeader& h, std::span<const uint8_t> data) {
  LittleEndianReader in(data);
  LittleEndianWriter w(reply_);
  switch (static_cast<Command>(h.commandId)) {
    case Command::ReadDeviceInfo: appendDeviceInfo(reply_, "TwinCAT System"); return AdsError::None;
    case Command::ReadState:
      w.u16(kAdsStateRun);
      w.u16(kSystemDeviceState);
      return AdsError::None;
    case Command::Read: {
      const uint32_t ig = *in.u32(), io = *in.u32(), length = *in.u32();
      w.u32(0);
      if (ig != static_cast<uint32_t>(IndexGroup::SystemState)) return AdsError::InvalidIndexGroup;
      if (io != 0) return AdsError::InvalidIndexOffset;
      if (length < 16) return AdsError::InvalidSize;
      // Extended system state (docs/ads.md, States and return codes): the system stays in RUN
      // whatever the PLC does.
      w.u16(kAdsStateRun);
      w.u16(kSystemDeviceState);
      w.u16(0);  // restartIndex: a change would make ads-client reconnect
      w.u8(kVersionMajor);
      w.u8(kVersionMinor);
      w.u16(kVersionBuild);
      w.u8(0);   // platform
      w.u8(0);   // osType
      w.u16(0);  // flags
      w.u16(0);  // reserved
      w.put32(4, 16);
      return AdsError::None;
    }
    default: return AdsError::ServiceNotSupported;
  }
}

}  // namespace virtcom::proto::ads

#include "proto/modbus/mbap.hpp"

#include "proto/modbus/byte_io.hpp"

namespace virtcom::proto::modbus {

FrameScan scanFrame(std::span<const uint8_t> buffer) {
  BigEndianReader in(buffer);
  auto transactionId = in.u16(), protocolId = in.u16(), length = in.u16();
  auto unitId = in.u8();
  if (!transactionId || !protocolId || !length || !unitId) {
    // Reject a wrong protocol id as soon as it is visible rather than waiting for the rest.
    if (protocolId && *protocolId != 0) return {FrameStatus::Malformed, 0, {}};
    return {FrameStatus::NeedMore, 0, {}};
  }
  MbapHeader h{*transactionId, *protocolId, *length, *unitId};
  if (h.protocolId != 0 || h.length < kMinMbapLength || h.length > kMaxMbapLength) return {FrameStatus::Malformed, 0, h};
  size_t total = kMbapHeaderSize - 1 + h.length;  // the length counts the unit id
  if (buffer.size() < total) return {FrameStatus::NeedMore, 0, h};
  return {FrameStatus::Complete, total, h};
}

size_t handleFrame(std::span<const uint8_t> frame, const ImageView& image, EditQueue& edits,
                   std::span<uint8_t, kMaxAduSize> response) {
  FrameScan scan = scanFrame(frame);
  if (scan.status != FrameStatus::Complete) return 0;
  std::span<const uint8_t> pdu = frame.subspan(kMbapHeaderSize, scan.size - kMbapHeaderSize);
  size_t pduSize = handlePdu(pdu, image, edits, response.subspan<kMbapHeaderSize, kMaxPduSize>());
  BigEndianWriter header(response.first<kMbapHeaderSize>());
  header.u16(scan.header.transactionId);
  header.u16(0);
  header.u16(static_cast<uint16_t>(pduSize + 1));
  header.u8(scan.header.unitId);
  return kMbapHeaderSize + pduSize;
}

}  // namespace virtcom::proto::modbus

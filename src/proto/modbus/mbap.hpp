#pragma once
// Modbus TCP framing: the MBAP header (MODBUS Messaging on TCP/IP Implementation Guide V1.0b,
// section 3.1.3) in front of a PDU.
//   bytes 0-1 transaction id (echoed), 2-3 protocol id (0 = Modbus),
//   4-5 length (unit id + PDU bytes), 6 unit id (echoed; any value accepted), then the PDU.
#include <cstddef>
#include <cstdint>
#include <span>

#include "proto/modbus/pdu.hpp"

namespace virtcom::proto::modbus {

inline constexpr size_t kMbapHeaderSize = 7;
inline constexpr size_t kMaxAduSize = kMbapHeaderSize + kMaxPduSize;  // 260
inline constexpr uint16_t kMinMbapLength = 2;                          // unit id + function code
inline constexpr uint16_t kMaxMbapLength = 1 + kMaxPduSize;            // 254

struct MbapHeader {
  uint16_t transactionId = 0;
  uint16_t protocolId = 0;
  uint16_t length = 0;
  uint8_t unitId = 0;
};

enum class FrameStatus {
  NeedMore,   // not a whole frame yet: read more bytes
  Complete,   // the first `size` bytes are one frame
  Malformed,  // not Modbus TCP (protocol id != 0, length out of 2..254): close the connection
};

struct FrameScan {
  FrameStatus status = FrameStatus::NeedMore;
  size_t size = 0;
  MbapHeader header;
};

// Looks at the start of a receive buffer. Never reads past `buffer`; allocates nothing.
FrameScan scanFrame(std::span<const uint8_t> buffer);

// Answers one complete frame (as found by scanFrame) into `response`; returns the response's
// length. The transaction and unit ids are echoed; see handlePdu for the PDU contract.
size_t handleFrame(std::span<const uint8_t> frame, const ImageView& image, EditQueue& edits,
                   std::span<uint8_t, kMaxAduSize> response);

}  // namespace virtcom::proto::modbus

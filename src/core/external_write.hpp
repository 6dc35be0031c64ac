#pragma once
// Who wrote into the PLC from outside (a client of a protocol server), and the hook through which
// the servers' write queues report each edit as they apply it at a scan boundary. The write audit
// (plc/write_audit.*) implements the hook, the queues (proto/*) call it: neither knows the other,
// and every protocol is audited by the same code.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "core/ams_net_id.hpp"

namespace virtcom {

enum class WriteProtocol : uint8_t { Ads, Modbus, OpcUa, Http };
inline constexpr size_t kWriteProtocolCount = 4;
std::string_view writeProtocolName(WriteProtocol p);  // "ads", "modbus", "opcua", "http"

struct ExternalWriter {
  WriteProtocol protocol = WriteProtocol::Ads;
  uint32_t ipv4 = 0;  // the peer's address and port
  uint16_t port = 0;
  bool hasNetId = false;  // ADS: the AmsNetId the peer's packets came from
  AmsNetId netId{};
  bool operator==(const ExternalWriter&) const = default;
};

class WriteObserver {
 public:
  virtual ~WriteObserver() = default;
  // Just before an edit lands. `target` is the image it lands in (ADS, OPC UA: the PLC's data
  // area; Modbus: one process area) and `address` the PLC address of target[0]; the edit covers
  // [offset, offset + size) of `target`, or when `bitMask` is non-zero only those bits of its
  // one byte. `target` stays valid until endEdits().
  virtual void beforeEdit(const ExternalWriter& writer, std::span<const uint8_t> target, uint32_t address, uint32_t offset,
                          uint32_t size, uint8_t bitMask) = 0;
  // After the last edit of a batch (one queue drained) has landed.
  virtual void endEdits() = 0;
};

}  // namespace virtcom

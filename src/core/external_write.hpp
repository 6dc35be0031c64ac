#pragma once
// Who wrote into the PLC from outside (a client of a protocol server or of the HMI), and the hook
// through which the servers' write queues (and the HMI's commands) report each edit as they apply
// it at a scan boundary. The write audit
// (core/write_audit.*) implements the hook, the queues (proto/*) call it: neither knows the other,
// and every protocol is audited by the same code.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "core/ams_net_id.hpp"

namespace virtcom {

enum class WriteProtocol : uint8_t { Ads, Modbus, OpcUa, Http };
inline constexpr size_t kWriteProtocolCount = 4;
std::string_view writeProtocolName(WriteProtocol p);  // "ads", "modbus", "opcua", "http"
// Writes counted by protocol, as the audit's summary and the reports say it:
// "3 external writes (ads 1, modbus 2, opcua 0, http 0)".
std::string externalWritesText(std::span<const uint64_t, kWriteProtocolCount> counts);

struct ExternalWriter {
  WriteProtocol protocol = WriteProtocol::Ads;
  uint32_t ipv4 = 0;  // the peer's address and port
  uint16_t port = 0;
  bool hasNetId = false;  // ADS: the AmsNetId the peer's packets came from
  AmsNetId netId{};
  bool force = false;  // HTTP: the HMI forced the value (written again around every scan until released)
  bool operator==(const ExternalWriter&) const = default;
};

// "127.0.0.1:50123": the writer's address and port.
std::string writerAddress(const ExternalWriter& w);
// writerAddress, and for ADS the AmsNetId: "127.0.0.1:50123 (AmsNetId 127.0.0.1.1.1)".
std::string writerPeer(const ExternalWriter& w);
// "2026-12-02T15:40:01.123Z": a wall time (UTC, ns since 1970) as the audit and the reports print it.
std::string utcTimeText(int64_t ns);

// One audited write (core/write_audit.hpp makes them): what the terminal log prints and the
// historian keeps (docs/history.md, table `writes`).
struct WriteRecord {
  int64_t virtualNs = 0;  // the scan boundary the write crossed
  int64_t wallNs = 0;     // UTC, ns since 1970
  ExternalWriter writer;
  std::string variable;  // qualified name ("MAIN.speed", "MAIN.a[3].x"); the location when none is declared there
  std::string location;  // the IEC address of a located variable ("%QX0.3", "%MW4"), else empty
  std::string oldValue, newValue;  // IEC literal text
};

// The variable a record names, with its IEC address when that says more: "MAIN.setpoint (%MW0)".
std::string writtenVariableText(const WriteRecord& r);

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
  // The PLC's state changed on a client's request (ADS WriteControl: RUN, STOP), from `from` to
  // `to` (the states' names), at a scan boundary.
  virtual void stateChanged(const ExternalWriter& writer, std::string_view from, std::string_view to) = 0;
};

}  // namespace virtcom

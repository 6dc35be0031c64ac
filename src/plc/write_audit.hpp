#pragma once
// The audit of writes from outside (docs/security.md, Audit of external writes): every edit a
// protocol server's write queue applies at a scan boundary becomes a record naming the time
// (virtual and wall), the protocol, the peer, the variable written and its old and new value as
// IEC text. One implementation for ADS, Modbus, OPC UA and the HMI's HTTP API
// (core/external_write.hpp); a client's change of the PLC's state (ADS WriteControl) is a record
// of the variable kPlcStateVariable.
// Nothing is allocated or looked up while no external write happens; the records of a batch are
// formatted (string work) only after it landed.
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "bytecode/variables.hpp"
#include "core/external_write.hpp"

namespace virtcom::plc {

// What a state change's record names as its variable: "ads 127.0.0.1:50123 PLC state: RUN -> STOP".
inline constexpr const char* kPlcStateVariable = "PLC state";

// "ads 127.0.0.1:50123 (AmsNetId 127.0.0.1.1.1) MAIN.speed: 0 -> 5" (times left to the caller);
// a force from the HMI ends in " (forced)".
std::string formatWriteRecord(const WriteRecord& r);
// "1.230s 2026-12-02T15:40:01.123Z " + formatWriteRecord(r): the terminal log's line body.
std::string formatWriteRecordWithTimes(const WriteRecord& r);

class WriteAudit final : public WriteObserver {
 public:
  using Sink = std::function<void(const WriteRecord&)>;
  // `module` must outlive the audit. `sink` receives every record (may be empty: counts only).
  WriteAudit(const bc::Module& module, Sink sink);

  // Scan thread, before the queues are drained: the virtual time the records carry.
  void setVirtualTime(int64_t ns) { virtualNs_ = ns; }

  void beforeEdit(const ExternalWriter& writer, std::span<const uint8_t> target, uint32_t address, uint32_t offset, uint32_t size,
                  uint8_t bitMask) override;
  void endEdits() override;
  void stateChanged(const ExternalWriter& writer, std::string_view from, std::string_view to) override;

  // Records so far, per protocol and in all.
  uint64_t count(WriteProtocol p) const { return counts_[static_cast<size_t>(p)]; }
  uint64_t total() const;

 private:
  struct Variable {  // a declared variable, top level (globals, program variables)
    std::string name;
    bc::VarRef ref;
    uint32_t size = 0;  // bytes (1 for a bit)
  };
  struct Pending {  // an edited variable of the current batch
    ExternalWriter writer;
    std::string name;  // the variable (narrowed to the member written), or empty: an undeclared location
    bc::VarRef ref;
    uint32_t size = 0;
    const uint8_t* at = nullptr;  // its first byte in the edited image (valid until endEdits)
    size_t oldPos = 0, newPos = 0;  // its bytes in bytes_
  };
  void closeOpen();
  WriteRecord toRecord(const Pending& p, int64_t wallNs);

  const bc::Module& m_;
  Sink sink_;
  std::vector<Variable> vars_;  // sorted by address
  std::vector<uint8_t> shadow_;  // the data area's size: where old and new bytes are formatted from
  std::vector<Pending> pending_, candidates_;
  std::vector<uint8_t> bytes_;
  size_t openFrom_ = 0;  // pending_[openFrom_..] still wait for their new bytes
  int64_t virtualNs_ = 0;
  std::array<uint64_t, kWriteProtocolCount> counts_{};
};

}  // namespace virtcom::plc

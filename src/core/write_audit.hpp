#pragma once
// The audit of writes from outside (docs/security.md, Audit of external writes): every edit a
// protocol server's write queue applies at a scan boundary becomes a record naming the time
// (virtual and wall), the protocol, the peer, the variable written and its old and new value as
// IEC text. One implementation for ADS, Modbus, OPC UA and the HMI's HTTP API
// (core/external_write.hpp), whatever the written image is: what its addresses name comes from
// an AuditedNames, the soft PLC's declared variables (plc/audited_variables.hpp) or a served
// cell's Modbus signals (proto/modbus/audited_signals.hpp). A client's change of the PLC's state
// (ADS WriteControl) is a record of the variable kPlcStateVariable.
// Nothing is allocated or looked up while no external write happens; the records of a batch are
// formatted (string work) only after it landed.
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/external_write.hpp"

namespace virtcom {

// What a state change's record names as its variable: "ads 127.0.0.1:50123 PLC state: RUN -> STOP".
inline constexpr const char* kPlcStateVariable = "PLC state";

// "ads 127.0.0.1:50123 (AmsNetId 127.0.0.1.1.1) MAIN.speed: 0 -> 5" (times left to the caller);
// a force from the HMI ends in " (forced)".
std::string formatWriteRecord(const WriteRecord& r);
// "1.230s 2026-12-02T15:40:01.123Z " + formatWriteRecord(r): the terminal log's line body.
std::string formatWriteRecordWithTimes(const WriteRecord& r);

// What the addresses of an audited image name, so that a record says "MAIN.speed (%MW0): 0 -> 5"
// or "Press.start (coil 3): FALSE -> TRUE" rather than bytes.
class AuditedNames {
 public:
  // A named place: the bytes [address, address + size), or one bit of the byte at `address`.
  struct Place {
    std::string name;  // empty: nothing is declared there (the generic text: location, raw value)
    uint32_t address = 0;
    int8_t bit = -1;
    uint32_t size = 0;  // bytes (1 for a bit)
    uint32_t what = 0;  // the implementation's own: what the value is (a type, a map entry)
  };
  virtual ~AuditedNames() = default;
  // Every named place, sorted by address.
  virtual const std::vector<Place>& places() const = 0;
  // `p` narrowed in place to its innermost part holding all of [lo, hi): a member, an element.
  virtual void narrow(Place& p, uint32_t lo, uint32_t hi) const;
  // The value `bytes` (p.size of them) hold as IEC literal text; nullopt: not formattable as
  // declared (the raw bytes are shown).
  virtual std::optional<std::string> valueText(const Place& p, std::span<const uint8_t> bytes) = 0;
  // Where `p` lies when that says more than its name ("%QX0.3", "coil 3"), else empty; also
  // for an unnamed place.
  virtual std::string location(const Place& p) const = 0;
};

class WriteAudit final : public WriteObserver {
 public:
  using Sink = std::function<void(const WriteRecord&)>;
  // `sink` receives every record (may be empty: counts only).
  WriteAudit(std::unique_ptr<AuditedNames> names, Sink sink);

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
  struct Pending {  // an edited place of the current batch
    ExternalWriter writer;
    AuditedNames::Place place;  // narrowed to the member written; unnamed: an undeclared location
    const uint8_t* at = nullptr;  // its first byte in the edited image (valid until endEdits)
    size_t oldPos = 0, newPos = 0;  // its bytes in bytes_
  };
  void closeOpen();
  WriteRecord toRecord(const Pending& p, int64_t wallNs);

  std::unique_ptr<AuditedNames> names_;
  Sink sink_;
  std::vector<Pending> pending_, candidates_;
  std::vector<uint8_t> bytes_;
  size_t openFrom_ = 0;  // pending_[openFrom_..] still wait for their new bytes
  int64_t virtualNs_ = 0;
  std::array<uint64_t, kWriteProtocolCount> counts_{};
};

}  // namespace virtcom

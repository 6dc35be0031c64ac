#include "proto/modbus/audited_signals.hpp"

#include <algorithm>
#include <cmath>

#include "core/iec_value.hpp"
#include "proto/modbus/signal_codec.hpp"

namespace virtcom::proto::modbus {

namespace {

class AuditedSignals final : public AuditedNames {
 public:
  explicit AuditedSignals(const SignalMap& map) : entries_(map.entries) {
    for (uint32_t i = 0; i < entries_.size(); ++i) {
      const MapEntry& e = entries_[i];
      const uint32_t base = tableBaseAddress(e.table);
      if (isBitTable(e.table)) places_.push_back({e.signal, base + e.address / 8u, static_cast<int8_t>(e.address % 8u), 1, i});
      else places_.push_back({e.signal, base + 2u * e.address, -1, 2u * e.width(), i});
    }
    std::stable_sort(places_.begin(), places_.end(), [](const Place& a, const Place& b) { return a.address < b.address; });
  }

  const std::vector<Place>& places() const override { return places_; }

  std::optional<std::string> valueText(const Place& p, std::span<const uint8_t> bytes) override {
    if (p.bit >= 0) return std::nullopt;  // a coil or discrete input: the audit's TRUE / FALSE
    const MapEntry& e = entries_[p.what];
    const double v = registerSignalValue(e, bytes);
    if (e.type == ValueType::Bool) return v != 0 ? "TRUE" : "FALSE";
    if (v == std::trunc(v) && std::abs(v) < 1e15) return std::to_string(static_cast<int64_t>(v));
    return formatLreal(v);
  }

  // "coil 3", "holding 4": the table and address as the cell file's `modbus: map:` writes them.
  std::string location(const Place& p) const override {
    for (Table t : kTables) {
      const uint32_t base = tableBaseAddress(t);
      if (p.address < base || p.address >= base + kTableAddressSpan) continue;
      const uint32_t at = isBitTable(t) ? (p.address - base) * 8 + static_cast<uint32_t>(std::max<int8_t>(p.bit, 0)) : (p.address - base) / 2;
      return std::string(tableName(t)) + " " + std::to_string(at);
    }
    return "";
  }

 private:
  std::vector<MapEntry> entries_;
  std::vector<Place> places_;
};

}  // namespace

std::unique_ptr<AuditedNames> auditedSignals(const SignalMap& map) { return std::make_unique<AuditedSignals>(map); }

}  // namespace virtcom::proto::modbus

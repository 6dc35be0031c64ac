#pragma once
// Moves mapped signals between the tag bus and Modbus tables kept as an ImageView with
// Layout::Tables (coils = bits of `outputs`, discrete inputs = bits of `inputs`, holding
// registers = words of `memory`, input registers = words of `registers`; see pdu.hpp).
// Per-tick code: no allocation, no lookups by name. Entries must lie inside the view
// (tablesFor() sizes a view for a map).
#include "core/tag_bus.hpp"
#include "proto/modbus/pdu.hpp"
#include "proto/modbus/server.hpp"
#include "proto/modbus/signal_map.hpp"

namespace virtcom::proto::modbus {

// The signal's value, divided by the scale and converted to the entry's type (rounded, then
// clamped to the type's range), into the entry's bits or registers.
void storeSignal(const MapEntry& e, const TagBus& bus, const ImageView& tables);
// The entry's bits or registers, times the scale, into the signal (converted to the tag's type).
void loadSignal(const MapEntry& e, const ImageView& tables, TagBus& bus);
// The signal value a register entry's registers (`registers` starts at its first) stand for.
double registerSignalValue(const MapEntry& e, std::span<const uint8_t> registers);

// The shape of the tables that hold every entry of `map` (one past the highest address of each
// table), with the Server role's read-only entries marked. Allocates: load time.
ImageShape tablesFor(const SignalMap& map);

// The area of a Layout::Tables view that holds a table.
Area areaOf(Table t);
// Where each table lies in the address space the write audit sees (ImageView::plcAddresses of a
// TableImage): apart, so that an edit's address names its table. Each span holds a table's
// 65,536 registers (or bits) as bytes.
inline constexpr uint32_t kTableAddressSpan = 1u << 17;
uint32_t tableBaseAddress(Table t);
// The bytes of one table in a Layout::Tables view, and one register in them (little endian).
std::span<uint8_t> tableBytes(const ImageView& tables, Table t);
uint16_t getRegister(std::span<const uint8_t> bytes, uint32_t reg);
void setRegister(std::span<uint8_t> bytes, uint32_t reg, uint16_t value);
bool getBit(std::span<const uint8_t> bytes, uint32_t bit);
void setBit(std::span<uint8_t> bytes, uint32_t bit, bool on);

// Owns zero-filled tables of a given shape and views them.
class TableImage {
 public:
  explicit TableImage(const ImageShape& shape);
  const ImageView& view() const { return view_; }

 private:
  std::vector<uint8_t> discrete_, coils_, holding_, input_;
  ImageView view_;
};

}  // namespace virtcom::proto::modbus

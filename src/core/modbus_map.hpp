#pragma once
// Which tag bus signal sits at which Modbus address, with which type, word order and scaling:
// the `modbus:` section of a cell file (a served cell) and the `map:` of `plc: modbus:` (the
// client bridge to an external PLC), or the automatic mapping. docs/modbus.md has the format.
// A description only, no sockets: the cell loader reads and checks it, proto/modbus serves and
// polls it, so it sits below both.
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/config_node.hpp"
#include "core/diagnostics.hpp"
#include "core/tag_bus.hpp"

namespace virtcom::modbus_map {

enum class Table : uint8_t { Coil, DiscreteInput, HoldingRegister, InputRegister };
inline constexpr std::array<Table, 4> kTables = {Table::Coil, Table::DiscreteInput, Table::HoldingRegister, Table::InputRegister};
const char* tableName(Table t);  // "coil", "discrete", "holding", "input" (the cell file's words)
inline bool isBitTable(Table t) { return t == Table::Coil || t == Table::DiscreteInput; }

enum class ValueType : uint8_t {
#define MODBUS_VALUE_TYPE(name, text, registers, isSigned, isFloat) name,
#include "core/modbus_value_types.def"
#undef MODBUS_VALUE_TYPE
};
const char* valueTypeName(ValueType t);
uint32_t registerCount(ValueType t);

// 32-bit values: which register carries the most significant word.
enum class WordOrder : uint8_t { HighFirst, LowFirst };

// Command: the controller writes it, the device reads it (a device input port).
// Status: the device writes it, the controller reads it (a device output port).
enum class SignalDir : uint8_t { Command, Status };

// A signal that can be mapped: one tag of the bus and who writes it.
struct BusSignal {
  TagId tag = kNoTag;
  std::string name;  // "Press.execute"
  ElemType type = ElemType::Bool;
  SignalDir dir = SignalDir::Command;
};

// Who the map is for. Server: virtcom serves the tables and the external PLC is the client, so
// commands go where a client can write (coils, holding registers). Client: the tables are the
// external PLC's; virtcom reads commands from them and writes status into coils/holding registers.
enum class MapRole : uint8_t { Server, Client };

struct MapEntry {
  TagId tag = kNoTag;
  std::string signal;
  SignalDir dir = SignalDir::Command;
  Table table = Table::Coil;
  uint16_t address = 0;  // PDU address, 0-based
  ValueType type = ValueType::Bool;
  WordOrder order = WordOrder::HighFirst;
  double scale = 1;       // signal value = register value * scale
  bool readOnly = false;  // Server role: the client may not write it (always so for status)
  uint32_t width() const { return isBitTable(table) ? 1 : registerCount(type); }
};

struct SignalMap {
  std::vector<MapEntry> entries;  // in file order (automatic: in signal order)
  bool automatic = false;
  TagId cycleDone = kNoTag;       // the controller's cycle marker, when the section maps it (`cycle_done:`)
};

// Reads `word_order:` and `map:` through `section` (the caller rejects the section's other
// unknown keys; null: no section) into a map for `role`. Without a `map:` list every signal is
// mapped automatically: commands to coils (BOOL) or holding registers, status to discrete
// inputs / input registers (Server role) or to coils / holding registers after the commands
// (Client role), each table from address 0 in signal order. Reports every problem at its
// position through the section's reader.
// With `cycleMarker` (the controller's cycle marker, a BOOL signal) the section's `cycle_done:`
// (a map with optional table, address, type, as a map entry without `signal:`) maps it too,
// after the other entries; without `cycleMarker` the key is left unread (an unknown key).
SignalMap parseSignalMap(ConfigReader* section, std::span<const BusSignal> signals, MapRole role, const BusSignal* cycleMarker = nullptr);

// The map as a table for the PLC programmer: CSV (RFC 4180, header line) or GitHub Markdown.
std::string formatMapCsv(const SignalMap& map);
std::string formatMapMarkdown(const SignalMap& map);

}  // namespace virtcom::modbus_map

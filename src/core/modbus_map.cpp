#include "core/modbus_map.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <sstream>

#include "core/ascii.hpp"

namespace virtcom::modbus_map {

namespace {

struct ValueTypeInfo {
  ValueType type;
  const char* text;
  uint32_t registers;
};

constexpr ValueTypeInfo kValueTypes[] = {
#define MODBUS_VALUE_TYPE(name, text, registers, isSigned, isFloat) {ValueType::name, text, registers},
#include "core/modbus_value_types.def"
#undef MODBUS_VALUE_TYPE
};


std::optional<Table> tableFromText(const std::string& text) {
  for (Table t : kTables)
    if (text == tableName(t)) return t;
  return std::nullopt;
}

std::optional<ValueType> valueTypeFromText(std::string text) {
  for (const auto& info : kValueTypes)
    if (iequalsAscii(text, info.text)) return info.type;
  return std::nullopt;
}

std::optional<WordOrder> wordOrderFromText(const std::string& text) {
  if (text == "high_first") return WordOrder::HighFirst;
  if (text == "low_first") return WordOrder::LowFirst;
  return std::nullopt;
}

// Where a signal goes when the map does not say: BOOL signals to bits, others to registers;
// the table a client can write for commands (Server role), and for status in the Client role.
Table defaultTable(const BusSignal& s, MapRole role) {
  bool bit = s.type == ElemType::Bool;
  bool writable = role == MapRole::Client || s.dir == SignalDir::Command;
  if (writable) return bit ? Table::Coil : Table::HoldingRegister;
  return bit ? Table::DiscreteInput : Table::InputRegister;
}

ValueType defaultType(ElemType t) {
  if (t == ElemType::Bool) return ValueType::Bool;
  if (isFloat(t)) return ValueType::Real;
  if (elemTypeInfo(t).sizeBytes > 2) return elemTypeInfo(t).kind == ElemKind::Unsigned ? ValueType::Udint : ValueType::Dint;
  return elemTypeInfo(t).kind == ElemKind::Unsigned ? ValueType::Uint : ValueType::Int;
}

std::string signalExamples(std::span<const BusSignal> signals) {
  std::string text;
  for (size_t i = 0; i < signals.size() && i < 3; ++i) text += (i ? ", " : "") + signals[i].name;
  return text.empty() ? "none: the cell has no devices" : text + (signals.size() > 3 ? ", ..." : "");
}

class MapParser {
 public:
  MapParser(std::span<const BusSignal> signals, MapRole role, Diagnostics& diags)
      : signals_(signals), role_(role), diags_(diags) {}

  SignalMap automatic(WordOrder order) {
    SignalMap map;
    map.automatic = true;
    // Client role: commands first, so the PLC's outputs and inputs form two blocks.
    for (SignalDir dir : {SignalDir::Command, SignalDir::Status})
      for (const BusSignal& s : signals_) {
        bool take = role_ == MapRole::Server ? dir == SignalDir::Command : s.dir == dir;
        if (!take) continue;
        map.entries.push_back(defaults(s, order));
        place(map.entries.back());
      }
    return map;
  }

  SignalMap explicitMap(const ConfigNode& list, WordOrder order) {
    SignalMap map;
    if (list.kind() != ConfigNode::Kind::List) {
      ConfigReader(list, diags_, "'map'").error(list.loc(), "'map' must be a list of entries with 'signal:' (and optional table, address, type, word_order, scale, read_only)");
      return map;
    }
    for (const ConfigNode& item : list.items()) {
      ConfigReader r(item, diags_, "a Modbus map entry");
      if (item.kind() != ConfigNode::Kind::Map) {
        r.error(item.loc(), "a map entry must be a map with 'signal:', e.g. { signal: Press.execute, table: coil, address: 0 }");
        continue;
      }
      if (auto entry = readEntry(r, item, order)) {
        if (checkOverlap(*entry, map, item.loc(), r)) map.entries.push_back(*entry);
      }
      r.rejectUnknownKeys();
    }
    return map;
  }

 private:
  MapEntry defaults(const BusSignal& s, WordOrder order) const {
    MapEntry e;
    e.tag = s.tag;
    e.signal = s.name;
    e.dir = s.dir;
    e.table = defaultTable(s, role_);
    e.type = isBitTable(e.table) ? ValueType::Bool : defaultType(s.type);
    e.order = order;
    e.readOnly = role_ == MapRole::Server && s.dir == SignalDir::Status;
    return e;
  }

  // Gives the entry the next free address of its table.
  void place(MapEntry& e) {
    uint32_t& next = nextFree_[static_cast<size_t>(e.table)];
    e.address = static_cast<uint16_t>(std::min<uint32_t>(next, 0xffff));
    next += e.width();
  }

  const BusSignal* findSignal(const std::string& name) const {
    for (const BusSignal& s : signals_)
      if (s.name == name) return &s;
    return nullptr;
  }

  std::optional<MapEntry> readEntry(ConfigReader& r, const ConfigNode& item, WordOrder order) {
    std::string name = r.requireString("signal");
    if (name.empty()) return std::nullopt;
    const BusSignal* s = findSignal(name);
    if (!s) {
      r.error(item.find("signal")->loc(), "no device signal '" + name + "' (signals are DEVICE.PORT, e.g. " + signalExamples(signals_) + ")");
      return std::nullopt;
    }
    return readPlacement(r, item, *s, order);
  }

 public:
  // `cycle_done: { table: discrete, address: 100 }`: the cycle marker `s`, placed as an entry.
  void addCycleMarker(SignalMap& map, const ConfigNode& node, const BusSignal& s, WordOrder order) {
    ConfigReader r(node, diags_, "'cycle_done'");
    if (node.kind() != ConfigNode::Kind::Map) return;  // the reader has reported that it must be a map
    if (auto entry = readPlacement(r, node, s, order)) {
      if (checkOverlap(*entry, map, node.loc(), r)) {
        map.entries.push_back(*entry);
        map.cycleDone = s.tag;
      }
    }
    r.rejectUnknownKeys();
  }

 private:
  // The table, address, type, word order, scale and access of the entry for `s` in `item`.
  std::optional<MapEntry> readPlacement(ConfigReader& r, const ConfigNode& item, const BusSignal& signal, WordOrder order) {
    const BusSignal* s = &signal;
    MapEntry e = defaults(*s, order);
    bool ok = true;
    if (const ConfigNode* t = r.child("table")) {
      if (auto table = tableFromText(t->scalar())) e.table = *table;
      else {
        r.error(t->loc(), "'table' must be coil, discrete, holding or input, not '" + t->scalar() + "'");
        ok = false;
      }
      e.type = isBitTable(e.table) ? ValueType::Bool : defaultType(s->type);
    }
    if (const ConfigNode* t = r.child("type")) {
      if (auto type = valueTypeFromText(t->scalar())) e.type = *type;
      else {
        // Device signals are numbers and bits on the tag bus; none carries text.
        const bool text = t->scalar() == "STRING" || t->scalar() == "string";
        r.error(t->loc(), "'type' must be BOOL, INT, UINT, DINT, UDINT or REAL, not '" + t->scalar() + "'" +
                              (text ? " (no device signal carries text, so a signal cannot be mapped as a STRING)" : ""));
        ok = false;
      }
    }
    if (const ConfigNode* w = r.child("word_order")) {
      if (auto wo = wordOrderFromText(w->scalar())) e.order = *wo;
      else {
        r.error(w->loc(), "'word_order' must be high_first or low_first, not '" + w->scalar() + "'");
        ok = false;
      }
    }
    e.scale = r.optNumber("scale", 1.0);
    e.readOnly = r.optBool("read_only", e.readOnly);
    ok = ok && r.ok() && checkEntry(e, *s, item, r);
    if (!ok) return std::nullopt;
    if (const ConfigNode* a = item.find("address")) {
      int64_t address = r.optInt("address", 0);
      if (address < 0 || address + e.width() > 65536) {
        r.error(a->loc(), "'address' must be 0.." + std::to_string(65536 - e.width()) + " for a " + valueTypeName(e.type));
        return std::nullopt;
      }
      e.address = static_cast<uint16_t>(address);
      uint32_t& next = nextFree_[static_cast<size_t>(e.table)];
      next = std::max(next, static_cast<uint32_t>(address) + e.width());
    } else {
      place(e);
    }
    return e;
  }

  bool checkEntry(const MapEntry& e, const BusSignal& s, const ConfigNode& item, ConfigReader& r) {
    SourceLocation at = item.find("table") ? item.find("table")->loc() : item.loc();
    bool clientWritable = e.table == Table::Coil || e.table == Table::HoldingRegister;
    if (role_ == MapRole::Server && s.dir == SignalDir::Command && !clientWritable) {
      r.error(at, "'" + s.name + "' is a command the external PLC writes: map it to a coil or holding register, not " +
                      tableName(e.table));
      return false;
    }
    if (role_ == MapRole::Client && s.dir == SignalDir::Status && !clientWritable) {
      r.error(at, "'" + s.name + "' is written to the external PLC: map it to a coil or holding register, not " +
                      tableName(e.table));
      return false;
    }
    if (role_ == MapRole::Server && s.dir == SignalDir::Status && item.find("read_only") && !e.readOnly) {
      r.error(item.find("read_only")->loc(), "'" + s.name + "' is a device status signal: it is always read-only");
      return false;
    }
    if (isBitTable(e.table) && e.type != ValueType::Bool) {
      r.error(item.find("type") ? item.find("type")->loc() : at, std::string("a ") + tableName(e.table) + " holds one bit: its type is BOOL");
      return false;
    }
    if (isBitTable(e.table) && s.type != ElemType::Bool) {
      r.error(at, "'" + s.name + "' is " + std::string(elemTypeInfo(s.type).name) + ": map it to a register, a " + tableName(e.table) + " holds one bit");
      return false;
    }
    if (e.scale == 0 || !std::isfinite(e.scale)) {
      r.error(item.find("scale")->loc(), "'scale' must be a non-zero number (signal value = register value * scale)");
      return false;
    }
    return true;
  }

  bool checkOverlap(const MapEntry& e, const SignalMap& map, SourceLocation loc, ConfigReader& r) {
    for (const MapEntry& other : map.entries) {
      if (other.dir == SignalDir::Command && other.tag == e.tag && e.dir == SignalDir::Command) {
        r.error(loc, "'" + e.signal + "' is mapped twice: a command has one writer");
        return false;
      }
      bool overlap = other.table == e.table && other.address < e.address + e.width() && e.address < other.address + other.width();
      if (overlap) {
        r.error(loc, std::string(tableName(e.table)) + " " + std::to_string(e.address) + " overlaps '" + other.signal + "' at " +
                         std::to_string(other.address));
        return false;
      }
    }
    return true;
  }

  std::span<const BusSignal> signals_;
  MapRole role_;
  Diagnostics& diags_;
  std::array<uint32_t, 4> nextFree_{};
};

std::string scaleText(const MapEntry& e) {
  if (e.type == ValueType::Bool) return "";
  std::ostringstream out;
  out << e.scale;
  return out.str();
}

const char* directionText(const MapEntry& e) { return e.dir == SignalDir::Command ? "command" : "status"; }
const char* accessText(const MapEntry& e) { return e.readOnly ? "read" : "read/write"; }

std::string orderText(const MapEntry& e) {
  if (registerCount(e.type) < 2 || isBitTable(e.table)) return "";
  return e.order == WordOrder::HighFirst ? "high_first" : "low_first";
}

}  // namespace

const char* tableName(Table t) {
  switch (t) {
    case Table::Coil: return "coil";
    case Table::DiscreteInput: return "discrete";
    case Table::HoldingRegister: return "holding";
    case Table::InputRegister: return "input";
  }
  return "?";
}

const char* valueTypeName(ValueType t) { return kValueTypes[static_cast<size_t>(t)].text; }
uint32_t registerCount(ValueType t) { return kValueTypes[static_cast<size_t>(t)].registers; }

SignalMap parseSignalMap(ConfigReader* section, std::span<const BusSignal> signals, MapRole role, const BusSignal* cycleMarker) {
  WordOrder order = WordOrder::HighFirst;
  if (!section) {
    Diagnostics unused;
    return MapParser(signals, role, unused).automatic(order);
  }
  MapParser parser(signals, role, section->diags());
  if (const ConfigNode* w = section->child("word_order")) {
    if (auto wo = wordOrderFromText(w->scalar())) order = *wo;
    else section->error(w->loc(), "'word_order' must be high_first or low_first, not '" + w->scalar() + "'");
  }
  const ConfigNode* list = section->child("map");
  SignalMap map = list ? parser.explicitMap(*list, order) : parser.automatic(order);
  if (const ConfigNode* marker = cycleMarker ? section->child("cycle_done") : nullptr)
    parser.addCycleMarker(map, *marker, *cycleMarker, order);
  return map;
}

std::string formatMapCsv(const SignalMap& map) {
  std::string out = "table,address,type,signal,direction,access,word_order,scale\n";
  for (const MapEntry& e : map.entries)
    out += std::string(tableName(e.table)) + "," + std::to_string(e.address) + "," + valueTypeName(e.type) + "," + e.signal + "," +
           directionText(e) + "," + accessText(e) + "," + orderText(e) + "," + scaleText(e) + "\n";
  return out;
}

std::string formatMapMarkdown(const SignalMap& map) {
  std::string out =
      "| table | address | type | signal | direction | access | word order | scale |\n"
      "| --- | ---: | --- | --- | --- | --- | --- | ---: |\n";
  for (const MapEntry& e : map.entries)
    out += std::string("| ") + tableName(e.table) + " | " + std::to_string(e.address) + " | " + valueTypeName(e.type) + " | `" +
           e.signal + "` | " + directionText(e) + " | " + accessText(e) + " | " + orderText(e) + " | " + scaleText(e) + " |\n";
  return out;
}

}  // namespace virtcom::modbus_map

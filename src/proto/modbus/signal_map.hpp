#pragma once
// The signal map this layer serves and polls is a description below it (core/modbus_map.hpp:
// the cell file declares it); named here so the Modbus code speaks of it unqualified.
#include "core/modbus_map.hpp"

namespace virtcom::proto::modbus {

using modbus_map::BusSignal;
using modbus_map::formatMapCsv;
using modbus_map::formatMapMarkdown;
using modbus_map::isBitTable;
using modbus_map::kTables;
using modbus_map::MapEntry;
using modbus_map::MapRole;
using modbus_map::parseSignalMap;
using modbus_map::registerCount;
using modbus_map::SignalDir;
using modbus_map::SignalMap;
using modbus_map::Table;
using modbus_map::tableName;
using modbus_map::ValueType;
using modbus_map::valueTypeName;
using modbus_map::WordOrder;

}  // namespace virtcom::proto::modbus

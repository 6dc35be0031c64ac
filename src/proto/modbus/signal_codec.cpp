#include "proto/modbus/signal_codec.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

namespace virtcom::proto::modbus {

namespace {

// The entry's registers (from `registers[0]`) as one 16- or 32-bit word, most significant word first.
uint32_t loadWord(const MapEntry& e, std::span<const uint8_t> registers) {
  if (registerCount(e.type) == 1) return getRegister(registers, 0);
  uint32_t first = getRegister(registers, 0), second = getRegister(registers, 1);
  return e.order == WordOrder::HighFirst ? (first << 16 | second) : (second << 16 | first);
}

void storeWord(const MapEntry& e, std::span<uint8_t> bytes, uint32_t word) {
  if (registerCount(e.type) == 1) return setRegister(bytes, e.address, static_cast<uint16_t>(word));
  auto high = static_cast<uint16_t>(word >> 16), low = static_cast<uint16_t>(word);
  setRegister(bytes, e.address, e.order == WordOrder::HighFirst ? high : low);
  setRegister(bytes, e.address + 1u, e.order == WordOrder::HighFirst ? low : high);
}

template <class T>
uint32_t clampTo(double v) {
  if (std::isnan(v)) return 0;
  double r = std::round(std::clamp(v, static_cast<double>(std::numeric_limits<T>::min()), static_cast<double>(std::numeric_limits<T>::max())));
  return static_cast<uint32_t>(static_cast<T>(r));
}

uint32_t encode(ValueType t, double v) {
  switch (t) {
    case ValueType::Bool: return v != 0 ? 1 : 0;
    case ValueType::Int: return clampTo<int16_t>(v) & 0xffff;
    case ValueType::Uint: return clampTo<uint16_t>(v);
    case ValueType::Dint: return clampTo<int32_t>(v);
    case ValueType::Udint: return clampTo<uint32_t>(v);
    case ValueType::Real: return std::bit_cast<uint32_t>(static_cast<float>(v));
  }
  return 0;
}

double decode(ValueType t, uint32_t w) {
  switch (t) {
    case ValueType::Bool: return w != 0 ? 1 : 0;
    case ValueType::Int: return static_cast<int16_t>(w);
    case ValueType::Uint: return static_cast<uint16_t>(w);
    case ValueType::Dint: return static_cast<int32_t>(w);
    case ValueType::Udint: return w;
    case ValueType::Real: return std::bit_cast<float>(w);
  }
  return 0;
}

}  // namespace

std::span<uint8_t> tableBytes(const ImageView& v, Table t) { return v.bytes(areaOf(t)); }

uint16_t getRegister(std::span<const uint8_t> bytes, uint32_t reg) {
  return static_cast<uint16_t>(bytes[2 * reg] | (bytes[2 * reg + 1] << 8));
}

void setRegister(std::span<uint8_t> bytes, uint32_t reg, uint16_t value) {
  bytes[2 * reg] = static_cast<uint8_t>(value);
  bytes[2 * reg + 1] = static_cast<uint8_t>(value >> 8);
}

void setBit(std::span<uint8_t> bytes, uint32_t bit, bool on) {
  auto mask = static_cast<uint8_t>(1u << (bit % 8));
  bytes[bit / 8] = static_cast<uint8_t>(on ? bytes[bit / 8] | mask : bytes[bit / 8] & ~mask);
}

bool getBit(std::span<const uint8_t> bytes, uint32_t bit) { return (bytes[bit / 8] >> (bit % 8)) & 1; }


void storeSignal(const MapEntry& e, const TagBus& bus, const ImageView& tables) {
  std::span<uint8_t> bytes = tableBytes(tables, e.table);
  if (isBitTable(e.table)) return setBit(bytes, e.address, bus.getNumber(e.tag) != 0);
  storeWord(e, bytes, encode(e.type, e.type == ValueType::Bool ? bus.getNumber(e.tag) : bus.getNumber(e.tag) / e.scale));
}

double registerSignalValue(const MapEntry& e, std::span<const uint8_t> registers) {
  double raw = decode(e.type, loadWord(e, registers));
  return e.type == ValueType::Bool ? raw : raw * e.scale;
}

void loadSignal(const MapEntry& e, const ImageView& tables, TagBus& bus) {
  std::span<const uint8_t> bytes = tableBytes(tables, e.table);
  if (isBitTable(e.table)) return bus.setNumber(e.tag, getBit(bytes, e.address) ? 1 : 0);
  bus.setNumber(e.tag, registerSignalValue(e, bytes.subspan(2u * e.address, 2u * e.width())));
}

ImageShape tablesFor(const SignalMap& map) {
  std::array<uint32_t, 4> end{};  // per Table: one past the highest bit or register
  for (const MapEntry& e : map.entries) {
    auto& x = end[static_cast<size_t>(e.table)];
    x = std::max(x, e.address + e.width());
  }
  auto bitBytes = [](uint32_t bits) { return (bits + 7u) / 8u; };
  ImageShape shape;
  shape.layout = Layout::Tables;
  shape.outputs = bitBytes(end[static_cast<size_t>(Table::Coil)]);
  shape.inputs = bitBytes(end[static_cast<size_t>(Table::DiscreteInput)]);
  shape.memory = 2 * end[static_cast<size_t>(Table::HoldingRegister)];
  shape.registers = 2 * end[static_cast<size_t>(Table::InputRegister)];
  shape.readOnlyCoils.assign(shape.outputs, 0);
  shape.readOnlyHolding.assign(bitBytes(end[static_cast<size_t>(Table::HoldingRegister)]), 0);
  for (const MapEntry& e : map.entries) {
    if (!e.readOnly) continue;
    if (e.table == Table::Coil) setBit(shape.readOnlyCoils, e.address, true);
    if (e.table == Table::HoldingRegister)
      for (uint32_t r = e.address; r < e.address + e.width(); ++r) setBit(shape.readOnlyHolding, r, true);
  }
  return shape;
}

TableImage::TableImage(const ImageShape& shape)
    : discrete_(shape.inputs, 0), coils_(shape.outputs, 0), holding_(shape.memory, 0), input_(shape.registers, 0),
      view_{discrete_, coils_, holding_, input_, Layout::Tables} {
  for (Table t : kTables)
    view_.plcAddresses[static_cast<size_t>(areaOf(t))] = tableBaseAddress(t);
}

Area areaOf(Table t) {
  switch (t) {
    case Table::Coil: return Area::Outputs;
    case Table::DiscreteInput: return Area::Inputs;
    case Table::HoldingRegister: return Area::Memory;
    case Table::InputRegister: return Area::Registers;
  }
  return Area::Outputs;
}

uint32_t tableBaseAddress(Table t) { return (static_cast<uint32_t>(t) + 1u) * kTableAddressSpan; }

}  // namespace virtcom::proto::modbus

#include "proto/modbus/pdu.hpp"

#include <optional>

#include "proto/modbus/byte_io.hpp"

namespace virtcom::proto::modbus {

namespace {

// Quantity limits: MODBUS Application Protocol V1.1b3 sections 6.1-6.17.
constexpr uint16_t kMaxReadBits = 2000;         // FC1, FC2
constexpr uint16_t kMaxReadRegisters = 125;     // FC3, FC4, FC23 read
constexpr uint16_t kMaxWriteCoils = 1968;       // FC15
constexpr uint16_t kMaxWriteRegisters = 123;    // FC16
constexpr uint16_t kMaxRwWriteRegisters = 121;  // FC23 write
constexpr uint16_t kCoilOn = 0xFF00, kCoilOff = 0x0000;  // FC5 output value

using Result = std::optional<ExceptionCode>;  // nullopt: the normal response was written

struct Context {
  BigEndianReader& in;
  const ImageView& image;
  EditQueue& edits;
  BigEndianWriter& out;
};

struct Location {
  Area area;
  uint32_t offset;  // byte offset of the register's low byte in its area
};

// Register `index` of a run of `words`-register values stored little endian from the start of
// `area`, highest word first on the wire (OpenPLC's order for %MD and %ML). The whole value
// must lie inside the area.
std::optional<Location> wordOfValue(const ImageView& image, Area area, uint32_t index, uint32_t words) {
  uint32_t value = index / words, wordFromHigh = index % words;
  uint64_t end = static_cast<uint64_t>(value + 1) * 2 * words;
  if (end > image.bytes(area).size()) return std::nullopt;
  return Location{area, value * 2 * words + 2 * (words - 1 - wordFromHigh)};
}

std::optional<Location> inputRegister(const ImageView& image, uint32_t reg) {
  return wordOfValue(image, image.layout == Layout::Tables ? Area::Registers : Area::Inputs, reg, 1);
}

std::optional<Location> holdingRegister(const ImageView& image, uint32_t reg) {
  if (image.layout == Layout::Tables) return wordOfValue(image, Area::Memory, reg, 1);
  if (reg < kMemoryRegisterBase) return wordOfValue(image, Area::Outputs, reg, 1);
  if (reg < kDoubleRegisterBase) return wordOfValue(image, Area::Memory, reg - kMemoryRegisterBase, 1);
  if (reg < kLongRegisterBase) return wordOfValue(image, Area::Memory, reg - kDoubleRegisterBase, 2);
  if (reg < kLongRegisterEnd) return wordOfValue(image, Area::Memory, reg - kLongRegisterBase, 4);
  // Discrete inputs and input registers are read-only by function code; a client that plays
  // the field (a simulated sensor) writes %IW, and the %IX bits in it, through this window.
  if (image.writableInputs && reg >= kInputHoldingBase) return wordOfValue(image, Area::Inputs, reg - kInputHoldingBase, 1);
  return std::nullopt;
}

bool bitSet(std::span<const uint8_t> bits, uint32_t i) { return i / 8 < bits.size() && ((bits[i / 8] >> (i % 8)) & 1); }

bool anyBitSet(std::span<const uint8_t> bits, uint32_t start, uint32_t count) {
  for (uint32_t i = start; i < start + count; ++i)
    if (bitSet(bits, i)) return true;
  return false;
}

using Locator = std::optional<Location> (*)(const ImageView&, uint32_t);

bool rangeExists(Locator locate, const ImageView& image, uint32_t start, uint32_t count) {
  for (uint32_t r = start; r < start + count; ++r)
    if (!locate(image, r)) return false;
  return true;
}

bool holdingWritable(const ImageView& image, uint32_t start, uint32_t count) {
  return rangeExists(holdingRegister, image, start, count) && !anyBitSet(image.readOnlyHolding, start, count);
}

bool bitRangeExists(std::span<const uint8_t> area, uint32_t start, uint32_t count) {
  return static_cast<uint64_t>(start) + count <= static_cast<uint64_t>(area.size()) * 8;
}

uint16_t loadRegister(const ImageView& image, Location loc) {
  auto b = image.bytes(loc.area);
  return static_cast<uint16_t>(b[loc.offset] | (b[loc.offset + 1] << 8));
}

// Reads a (start, quantity) pair and checks the quantity, then that the request has no more data.
Result readRange(BigEndianReader& in, uint16_t maxCount, uint16_t& start, uint16_t& count) {
  auto s = in.u16(), c = in.u16();
  if (!s || !c || in.remaining() != 0) return ExceptionCode::IllegalDataValue;
  if (*c < 1 || *c > maxCount) return ExceptionCode::IllegalDataValue;
  start = *s;
  count = *c;
  return std::nullopt;
}

Result readBits(Context& c, std::span<const uint8_t> area) {
  uint16_t start = 0, count = 0;
  if (auto e = readRange(c.in, kMaxReadBits, start, count)) return e;
  if (!bitRangeExists(area, start, count)) return ExceptionCode::IllegalDataAddress;
  c.out.u8(static_cast<uint8_t>((count + 7) / 8));  // byte count
  uint8_t packed = 0;
  for (uint32_t i = 0; i < count; ++i) {
    uint32_t bit = start + i;
    if ((area[bit / 8] >> (bit % 8)) & 1) packed = static_cast<uint8_t>(packed | (1u << (i % 8)));
    if (i % 8 == 7 || i + 1 == count) {
      c.out.u8(packed);
      packed = 0;
    }
  }
  return std::nullopt;
}

Result readRegisters(Context& c, Locator locate) {
  uint16_t start = 0, count = 0;
  if (auto e = readRange(c.in, kMaxReadRegisters, start, count)) return e;
  if (!rangeExists(locate, c.image, start, count)) return ExceptionCode::IllegalDataAddress;
  c.out.u8(static_cast<uint8_t>(2 * count));
  for (uint32_t r = start; r < static_cast<uint32_t>(start) + count; ++r) c.out.u16(loadRegister(c.image, *locate(c.image, r)));
  return std::nullopt;
}

void commit(Context& c, const ByteEdit& e) {
  applyEdit(e, c.image);
  c.edits.push(e);
}

// Queues registers[0..count) from wire bytes `values` at holding registers start..; checked before.
void writeRegisters(Context& c, uint32_t start, uint32_t count, std::span<const uint8_t> values) {
  for (uint32_t i = 0; i < count; ++i) {
    Location loc = *holdingRegister(c.image, start + i);
    commit(c, {loc.area, loc.offset, values[2 * i + 1], 0xff});  // low byte first in the image
    commit(c, {loc.area, loc.offset + 1, values[2 * i], 0xff});
  }
}

Result readCoils(Context& c) { return readBits(c, c.image.outputs); }
Result readDiscreteInputs(Context& c) { return readBits(c, c.image.inputs); }
Result readHoldingRegisters(Context& c) { return readRegisters(c, holdingRegister); }
Result readInputRegisters(Context& c) { return readRegisters(c, inputRegister); }

Result writeSingleCoil(Context& c) {
  auto addr = c.in.u16(), value = c.in.u16();
  if (!addr || !value || c.in.remaining() != 0) return ExceptionCode::IllegalDataValue;
  if (*value != kCoilOn && *value != kCoilOff) return ExceptionCode::IllegalDataValue;
  if (!bitRangeExists(c.image.outputs, *addr, 1) || bitSet(c.image.readOnlyCoils, *addr)) return ExceptionCode::IllegalDataAddress;
  if (!c.edits.hasRoom(1)) return ExceptionCode::ServerDeviceBusy;
  uint8_t bit = static_cast<uint8_t>(1u << (*addr % 8));
  commit(c, {Area::Outputs, *addr / 8u, *value == kCoilOn ? bit : uint8_t{0}, bit});
  c.out.u16(*addr);  // the response echoes the request
  c.out.u16(*value);
  return std::nullopt;
}

Result writeSingleRegister(Context& c) {
  auto addr = c.in.u16();
  auto value = c.in.bytes(2);
  if (!addr || !value || c.in.remaining() != 0) return ExceptionCode::IllegalDataValue;
  if (!holdingWritable(c.image, *addr, 1)) return ExceptionCode::IllegalDataAddress;
  if (!c.edits.hasRoom(2)) return ExceptionCode::ServerDeviceBusy;
  writeRegisters(c, *addr, 1, *value);
  c.out.u16(*addr);
  c.out.u8((*value)[0]);
  c.out.u8((*value)[1]);
  return std::nullopt;
}

Result writeMultipleCoils(Context& c) {
  auto start = c.in.u16(), count = c.in.u16();
  auto byteCount = c.in.u8();
  if (!start || !count || !byteCount) return ExceptionCode::IllegalDataValue;
  if (*count < 1 || *count > kMaxWriteCoils || *byteCount != (*count + 7) / 8 || c.in.remaining() != *byteCount)
    return ExceptionCode::IllegalDataValue;
  auto values = *c.in.bytes(*byteCount);
  if (!bitRangeExists(c.image.outputs, *start, *count) || anyBitSet(c.image.readOnlyCoils, *start, *count))
    return ExceptionCode::IllegalDataAddress;
  uint32_t first = *start / 8u, last = (*start + *count - 1u) / 8u;
  if (!c.edits.hasRoom(last - first + 1)) return ExceptionCode::ServerDeviceBusy;
  for (uint32_t byte = first; byte <= last; ++byte) {
    ByteEdit e{Area::Outputs, byte, 0, 0};
    for (uint32_t k = 0; k < 8; ++k) {
      uint32_t coil = byte * 8 + k;
      if (coil < *start || coil >= static_cast<uint32_t>(*start) + *count) continue;
      uint32_t i = coil - *start;
      e.mask = static_cast<uint8_t>(e.mask | (1u << k));
      if ((values[i / 8] >> (i % 8)) & 1) e.value = static_cast<uint8_t>(e.value | (1u << k));
    }
    commit(c, e);
  }
  c.out.u16(*start);
  c.out.u16(*count);
  return std::nullopt;
}

Result writeMultipleRegisters(Context& c) {
  auto start = c.in.u16(), count = c.in.u16();
  auto byteCount = c.in.u8();
  if (!start || !count || !byteCount) return ExceptionCode::IllegalDataValue;
  if (*count < 1 || *count > kMaxWriteRegisters || *byteCount != 2 * *count || c.in.remaining() != *byteCount)
    return ExceptionCode::IllegalDataValue;
  auto values = *c.in.bytes(*byteCount);
  if (!holdingWritable(c.image, *start, *count)) return ExceptionCode::IllegalDataAddress;
  if (!c.edits.hasRoom(2u * *count)) return ExceptionCode::ServerDeviceBusy;
  writeRegisters(c, *start, *count, values);
  c.out.u16(*start);
  c.out.u16(*count);
  return std::nullopt;
}

// FC23: the write is performed before the read (V1.1b3 section 6.17).
Result readWriteMultipleRegisters(Context& c) {
  auto readStart = c.in.u16(), readCount = c.in.u16(), writeStart = c.in.u16(), writeCount = c.in.u16();
  auto byteCount = c.in.u8();
  if (!readStart || !readCount || !writeStart || !writeCount || !byteCount) return ExceptionCode::IllegalDataValue;
  if (*readCount < 1 || *readCount > kMaxReadRegisters || *writeCount < 1 || *writeCount > kMaxRwWriteRegisters ||
      *byteCount != 2 * *writeCount || c.in.remaining() != *byteCount)
    return ExceptionCode::IllegalDataValue;
  auto values = *c.in.bytes(*byteCount);
  if (!rangeExists(holdingRegister, c.image, *readStart, *readCount) ||
      !holdingWritable(c.image, *writeStart, *writeCount))
    return ExceptionCode::IllegalDataAddress;
  if (!c.edits.hasRoom(2u * *writeCount)) return ExceptionCode::ServerDeviceBusy;
  writeRegisters(c, *writeStart, *writeCount, values);
  c.out.u8(static_cast<uint8_t>(2 * *readCount));
  for (uint32_t r = *readStart; r < static_cast<uint32_t>(*readStart) + *readCount; ++r)
    c.out.u16(loadRegister(c.image, *holdingRegister(c.image, r)));
  return std::nullopt;
}

}  // namespace

const char* functionName(uint8_t code) {
  switch (code) {
#define MODBUS_FUNCTION(name, value, handler, writes, text) \
  case value: return text;
#include "proto/modbus/function_codes.def"
#undef MODBUS_FUNCTION
  }
  return nullptr;
}

void applyEdit(const ByteEdit& e, const ImageView& image) {
  auto bytes = image.bytes(e.area);
  if (e.offset >= bytes.size()) return;
  bytes[e.offset] = static_cast<uint8_t>((bytes[e.offset] & ~e.mask) | (e.value & e.mask));
}

void EditQueue::applyTo(const ImageView& image, WriteObserver* audit) const {
  for (size_t i = 0; i < edits_.size(); ++i) {
    const ByteEdit& e = edits_[i];
    if (audit) {
      const uint8_t bits = e.mask == 0xff ? 0 : e.mask;
      audit->beforeEdit(writers_[i], image.bytes(e.area), image.plcAddresses[static_cast<size_t>(e.area)], e.offset, 1, bits);
    }
    applyEdit(e, image);
  }
  if (audit && !edits_.empty()) audit->endEdits();
}

size_t handlePdu(std::span<const uint8_t> request, const ImageView& image, EditQueue& edits,
                 std::span<uint8_t, kMaxPduSize> response) {
  BigEndianReader in(request);
  auto fc = in.u8();
  if (!fc) {  // an empty PDU has no function to answer; callers never pass one (MBAP length >= 2)
    BigEndianWriter out(response);
    out.u8(0x80);
    out.u8(static_cast<uint8_t>(ExceptionCode::IllegalFunction));
    return out.size();
  }
  BigEndianWriter out(response);
  out.u8(*fc);
  Context c{in, image, edits, out};
  Result result = ExceptionCode::IllegalFunction;
  switch (*fc) {
#define MODBUS_FUNCTION(name, value, handler, writes, text) \
  case value: result = writes && image.readOnly ? Result(ExceptionCode::IllegalFunction) : handler(c); break;
#include "proto/modbus/function_codes.def"
#undef MODBUS_FUNCTION
  }
  if (!result) return out.size();
  BigEndianWriter error(response);
  error.u8(static_cast<uint8_t>(*fc | 0x80));
  error.u8(static_cast<uint8_t>(*result));
  return error.size();
}

}  // namespace virtcom::proto::modbus

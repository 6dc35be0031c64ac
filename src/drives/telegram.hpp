#pragma once
// Drive telegrams as data: every telegram (telegrams.def), every bit and multi-bit field of its
// control/status words (word_layouts.def) and every unit (units.def) comes from one table, and
// the generic codec below packs/unpacks them. Nothing here is written per telegram.
//
// Values travel in three forms:
//   wire image   bytes as on the fieldbus, in the telegram's byte order (Big: PROFINET,
//                Little: EtherNet/IP), 32-bit values as one 4-byte unit (docs/drives.md);
//   raw words    one uint32_t per telegram word, index = position in words(telegram, dir), the
//                word's bit pattern zero-extended (an I16 of -8192 is 0xE000, an F32 its bits);
//   numbers      signedValue()/realValue() and the normalisation helpers (normalisation.hpp).
// Lookups by name are constexpr, so the simulators resolve slots and bits at compile time:
//   constexpr WordSlot kStw1 = wordSlot(TelegramId::Std1, Dir::ToDrive, "STW1");
//   constexpr BitDef kOn = bitDef(Layout::Stw1Speed, "On");
// and the per-tick code uses only indices and masks.
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <span>
#include <string_view>

#include "core/iec_value.hpp"

namespace virtcom::drives {

enum class TelegramId : uint8_t {
#define VIRTCOM_TELEGRAM(id, key, title, order, toBytes, fromBytes, source) id,
#include "drives/telegrams.def"
};
inline constexpr size_t kTelegramCount = 0
#define VIRTCOM_TELEGRAM(id, key, title, order, toBytes, fromBytes, source) +1
#include "drives/telegrams.def"
    ;

enum class Layout : uint8_t {
  None,
#define VIRTCOM_LAYOUT(layout, word, doc) layout,
#include "drives/word_layouts.def"
};

enum class Unit : uint8_t {
#define X(u, name, doc) u,
#include "drives/units.def"
#undef X
};

enum class ByteOrder : uint8_t { Big, Little };
enum class Dir : uint8_t { ToDrive, FromDrive };  // controller -> drive, drive -> controller
enum class WireType : uint8_t { Bits16, Bits32, I16, U16, I32, F32 };

struct TelegramDef {
  TelegramId id;
  std::string_view key;     // cell files and mapping files name telegrams by this
  std::string_view title;
  ByteOrder order;
  uint16_t toDriveBytes, fromDriveBytes;
  std::string_view source;  // where the layout is specified
};

struct WordDef {
  TelegramId telegram;
  Dir dir;
  std::string_view name;
  uint16_t offset;  // byte offset in the image
  WireType type;
  Unit unit;
  Layout layout;    // bit layout of a control/status word, None for numbers
  std::string_view doc;
};

// A bit (width 1) or a multi-bit field of a word.
struct BitDef {
  Layout layout = Layout::None;
  uint8_t lsb = 0;
  uint8_t width = 0;
  std::string_view name;
  std::string_view doc;
  constexpr uint32_t mask() const { return (width >= 32 ? 0xffffffffu : ((1u << width) - 1u)) << lsb; }
};

struct LayoutDef {
  Layout layout;
  std::string_view word;
  std::string_view doc;
};

struct UnitDef {
  Unit unit;
  std::string_view name;
  std::string_view doc;
};

// Where a word lives: its index in the raw-word array of one direction.
struct WordSlot {
  TelegramId telegram;
  Dir dir;
  uint8_t index;
};

// Largest number of words in one direction of any telegram (telegram 111: 10).
inline constexpr size_t kMaxWords = 10;
inline constexpr size_t kMaxImageBytes = 24;
using RawWords = std::array<uint32_t, kMaxWords>;

namespace detail {
inline constexpr TelegramDef kTelegrams[] = {
#define VIRTCOM_TELEGRAM(id, key, title, order, toBytes, fromBytes, source) \
  {TelegramId::id, key, title, ByteOrder::order, toBytes, fromBytes, source},
#include "drives/telegrams.def"
};
inline constexpr WordDef kWords[] = {
#define VIRTCOM_TG_WORD(id, dir, name, offset, type, unit, layout, doc) \
  {TelegramId::id, Dir::dir, #name, offset, WireType::type, Unit::unit, Layout::layout, doc},
#include "drives/telegrams.def"
};
inline constexpr LayoutDef kLayouts[] = {
#define VIRTCOM_LAYOUT(layout, word, doc) {Layout::layout, word, doc},
#include "drives/word_layouts.def"
};
inline constexpr BitDef kBits[] = {
#define VIRTCOM_BIT(layout, lsb, width, name, doc) {Layout::layout, lsb, width, #name, doc},
#include "drives/word_layouts.def"
};
inline constexpr UnitDef kUnits[] = {
#define X(u, name, doc) {Unit::u, name, doc},
#include "drives/units.def"
#undef X
};

constexpr size_t firstWord(TelegramId t, Dir d) {
  for (size_t i = 0; i < std::size(kWords); ++i)
    if (kWords[i].telegram == t && kWords[i].dir == d) return i;
  return std::size(kWords);
}
constexpr size_t wordCount(TelegramId t, Dir d) {
  size_t n = 0;
  for (const auto& w : kWords) n += w.telegram == t && w.dir == d;
  return n;
}
// Each telegram direction's [first, first + count) in kWords, computed at compile time: words()
// is on the per-tick path of every drive and must not scan the table.
struct WordRange {
  size_t first, count;
};
inline constexpr auto kWordRanges = [] {
  std::array<WordRange, std::size(kTelegrams) * 2> r{};
  for (size_t t = 0; t < std::size(kTelegrams); ++t)
    for (Dir d : {Dir::ToDrive, Dir::FromDrive})
      r[t * 2 + static_cast<size_t>(d)] = {firstWord(kTelegrams[t].id, d), wordCount(kTelegrams[t].id, d)};
  return r;
}();
constexpr size_t firstBit(Layout l) {
  for (size_t i = 0; i < std::size(kBits); ++i)
    if (kBits[i].layout == l) return i;
  return std::size(kBits);
}
constexpr size_t bitCount(Layout l) {
  size_t n = 0;
  for (const auto& b : kBits) n += b.layout == l;
  return n;
}
// Invalid references in a constant expression fail to compile here.
inline void notFound() {}
}  // namespace detail

constexpr std::span<const TelegramDef> telegrams() { return detail::kTelegrams; }
constexpr const TelegramDef& telegram(TelegramId id) { return detail::kTelegrams[static_cast<size_t>(id)]; }
constexpr std::span<const LayoutDef> layouts() { return detail::kLayouts; }
constexpr const LayoutDef& layout(Layout l) { return detail::kLayouts[static_cast<size_t>(l) - 1]; }
constexpr const UnitDef& unit(Unit u) { return detail::kUnits[static_cast<size_t>(u)]; }
constexpr std::span<const UnitDef> units() { return detail::kUnits; }

// The words of one direction of a telegram, in offset order.
constexpr std::span<const WordDef> words(TelegramId t, Dir d) {
  const detail::WordRange r = detail::kWordRanges[static_cast<size_t>(t) * 2 + static_cast<size_t>(d)];
  return std::span<const WordDef>(detail::kWords).subspan(r.first, r.count);
}
constexpr const WordDef& word(WordSlot s) { return words(s.telegram, s.dir)[s.index]; }
// The bits and fields of a word layout, in bit order.
constexpr std::span<const BitDef> bits(Layout l) {
  return std::span<const BitDef>(detail::kBits).subspan(detail::firstBit(l), detail::bitCount(l));
}

// Lookups by exact name. The constexpr forms are meant for constant initialisers: a name that is
// not in the table makes the initialiser fail to compile. find*() return nullopt/nullptr.
constexpr std::optional<WordSlot> findWord(TelegramId t, Dir d, std::string_view name) {
  auto ws = words(t, d);
  for (size_t i = 0; i < ws.size(); ++i)
    if (ws[i].name == name) return WordSlot{t, d, static_cast<uint8_t>(i)};
  return std::nullopt;
}
constexpr WordSlot wordSlot(TelegramId t, Dir d, std::string_view name) {
  auto s = findWord(t, d, name);
  if (!s) detail::notFound();
  return *s;
}
constexpr const BitDef* findBit(Layout l, std::string_view name) {
  for (const BitDef& b : detail::kBits)
    if (b.layout == l && b.name == name) return &b;
  return nullptr;
}
constexpr BitDef bitDef(Layout l, std::string_view name) {
  for (const BitDef& b : detail::kBits)
    if (b.layout == l && b.name == name) return b;
  detail::notFound();
  return {};
}
std::optional<TelegramId> findTelegram(std::string_view key);

// Bits and fields of a raw word.
constexpr bool test(uint32_t word, BitDef b) { return (word & b.mask()) != 0; }
constexpr uint32_t field(uint32_t word, BitDef b) { return (word & b.mask()) >> b.lsb; }
constexpr uint32_t withField(uint32_t word, BitDef b, uint32_t value) {
  return (word & ~b.mask()) | ((value << b.lsb) & b.mask());
}
constexpr uint32_t withBit(uint32_t word, BitDef b, bool on) { return withField(word, b, on ? 1u : 0u); }

constexpr size_t wireBytes(WireType t) {
  return t == WireType::Bits32 || t == WireType::I32 || t == WireType::F32 ? 4 : 2;
}
// The IEC type a PLC variable for this word has (STRUCT member, port type).
ElemType elemType(WireType t);
std::string_view wireTypeName(WireType t);

// Raw word <-> number. signedValue sign-extends I16/I32; F32 words use realValue/rawFromReal.
constexpr int64_t signedValue(WireType t, uint32_t raw) {
  switch (t) {
    case WireType::I16: return static_cast<int16_t>(raw & 0xffffu);
    case WireType::I32: return static_cast<int32_t>(raw);
    default: return raw;
  }
}
// The raw pattern of an integer, truncated to the word's width (two's complement).
constexpr uint32_t rawFromInt(WireType t, int64_t v) {
  return wireBytes(t) == 2 ? static_cast<uint32_t>(v) & 0xffffu : static_cast<uint32_t>(v);
}
inline double realValue(uint32_t raw) { return std::bit_cast<float>(raw); }
inline uint32_t rawFromReal(double v) { return std::bit_cast<uint32_t>(static_cast<float>(v)); }

// One value at `offset` of a wire image in `order`. The caller guarantees the bounds (the
// telegram tables do, and the mapping validator checks user offsets). Never allocates. Inline,
// one load/store and at most one byte swap: every mapped drive runs them for every word, every tick.
inline uint32_t readWire(std::span<const uint8_t> image, size_t offset, WireType type, ByteOrder order) {
  const bool swap = (order == ByteOrder::Big) == (std::endian::native == std::endian::little);
  if (wireBytes(type) == 2) {
    uint16_t v;
    std::memcpy(&v, image.data() + offset, 2);
    return swap ? std::byteswap(v) : v;
  }
  uint32_t v;
  std::memcpy(&v, image.data() + offset, 4);
  return swap ? std::byteswap(v) : v;
}
inline void writeWire(std::span<uint8_t> image, size_t offset, WireType type, ByteOrder order, uint32_t raw) {
  const bool swap = (order == ByteOrder::Big) == (std::endian::native == std::endian::little);
  if (wireBytes(type) == 2) {
    const auto v = static_cast<uint16_t>(raw);
    const uint16_t wire = swap ? std::byteswap(v) : v;
    std::memcpy(image.data() + offset, &wire, 2);
    return;
  }
  const uint32_t wire = swap ? std::byteswap(raw) : raw;
  std::memcpy(image.data() + offset, &wire, 4);
}

// Whole-direction codec: words(t, d)[i] <-> raw[i]. The image must hold at least the
// telegram's byte count for that direction (false, nothing touched, if it is shorter).
// Never allocates.
bool encode(TelegramId t, Dir d, std::span<const uint32_t> raw, std::span<uint8_t> image);
bool decode(TelegramId t, Dir d, std::span<const uint8_t> image, std::span<uint32_t> raw);
constexpr size_t imageBytes(TelegramId t, Dir d) {
  return d == Dir::ToDrive ? telegram(t).toDriveBytes : telegram(t).fromDriveBytes;
}

}  // namespace virtcom::drives

#include "drives/telegram.hpp"

namespace virtcom::drives {
namespace {

// The tables' own invariants, checked once at compile time: telegram rows in enum order, the
// words of each direction contiguous, inside the image, non-overlapping and in offset order,
// bits of each layout contiguous and inside a 32-bit word.
constexpr bool wordsWellFormed() {
  for (size_t t = 0; t < kTelegramCount; ++t) {
    if (static_cast<size_t>(detail::kTelegrams[t].id) != t) return false;
    for (Dir d : {Dir::ToDrive, Dir::FromDrive}) {
      const auto id = static_cast<TelegramId>(t);
      const auto ws = words(id, d);
      if (ws.size() > kMaxWords || imageBytes(id, d) > kMaxImageBytes) return false;
      size_t end = 0;
      for (const WordDef& w : ws) {
        if (w.telegram != id || w.dir != d || w.offset < end) return false;
        end = w.offset + wireBytes(w.type);
      }
      if (end > imageBytes(id, d)) return false;
    }
  }
  return true;
}
constexpr bool bitsWellFormed() {
  for (const LayoutDef& l : detail::kLayouts) {
    uint32_t used = 0;
    for (const BitDef& b : bits(l.layout)) {
      if (b.layout != l.layout || b.width == 0 || b.lsb + b.width > 32 || (used & b.mask())) return false;
      used |= b.mask();
    }
  }
  size_t total = 0;
  for (const LayoutDef& l : detail::kLayouts) total += bits(l.layout).size();
  return total == std::size(detail::kBits);
}
static_assert(wordsWellFormed(), "telegrams.def: words must be grouped, ordered and inside the image");
static_assert(bitsWellFormed(), "word_layouts.def: bits must be grouped per layout and not overlap");

}  // namespace

std::optional<TelegramId> findTelegram(std::string_view key) {
  for (const TelegramDef& t : telegrams())
    if (t.key == key) return t.id;
  return std::nullopt;
}

ElemType elemType(WireType t) {
  switch (t) {
    case WireType::Bits16: return ElemType::Word;
    case WireType::Bits32: return ElemType::Dword;
    case WireType::I16: return ElemType::Int;
    case WireType::U16: return ElemType::Uint;
    case WireType::I32: return ElemType::Dint;
    case WireType::F32: return ElemType::Real;
  }
  return ElemType::Word;
}

std::string_view wireTypeName(WireType t) {
  switch (t) {
    case WireType::Bits16: return "bits16";
    case WireType::Bits32: return "bits32";
    case WireType::I16: return "i16";
    case WireType::U16: return "u16";
    case WireType::I32: return "i32";
    case WireType::F32: return "f32";
  }
  return "?";
}

bool encode(TelegramId t, Dir d, std::span<const uint32_t> raw, std::span<uint8_t> image) {
  const auto ws = words(t, d);
  if (image.size() < imageBytes(t, d) || raw.size() < ws.size()) return false;
  for (size_t i = 0; i < ws.size(); ++i) writeWire(image, ws[i].offset, ws[i].type, telegram(t).order, raw[i]);
  return true;
}

bool decode(TelegramId t, Dir d, std::span<const uint8_t> image, std::span<uint32_t> raw) {
  const auto ws = words(t, d);
  if (image.size() < imageBytes(t, d) || raw.size() < ws.size()) return false;
  for (size_t i = 0; i < ws.size(); ++i) raw[i] = readWire(image, ws[i].offset, ws[i].type, telegram(t).order);
  return true;
}

}  // namespace virtcom::drives

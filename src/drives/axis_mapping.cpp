// MappingRuntime: applies a validated mapping between UNIVERSAL_AXIS signals and raw telegram
// words every tick (no allocation, no lookups), and the signal table.
#include "drives/axis_mapping.hpp"

#include <bit>

#include "drives/normalisation.hpp"

namespace virtcom::drives {
namespace {

constexpr AxisSignalDef kSignals[] = {
#define VIRTCOM_AXIS_SIGNAL(id, type, kind, required, doc) \
  {AxisSignal::id, #id, ElemType::type, SignalKind::kind, required, doc},
#include "drives/axis_signals.def"
};

constexpr uint32_t fieldMask(WordBits at) {
  return at.width >= 32 ? 0xffffffffu : ((1u << at.width) - 1u) << at.lsb;
}

void put(uint32_t& word, WordBits at, uint32_t value) {
  const uint32_t mask = fieldMask(at);
  word = (word & ~mask) | ((value << at.lsb) & mask);
}

uint32_t get(uint32_t word, WordBits at) { return (word & fieldMask(at)) >> at.lsb; }

// A raw word written to a wire image in one byte order and read back in the other (`swap`) or
// the same: what writeWire() then readWire() give, without the image.
uint32_t overTheWire(uint32_t raw, bool wide, bool swap) {
  if (!wide) {
    const auto v = static_cast<uint16_t>(raw);
    return swap ? std::byteswap(v) : v;
  }
  return swap ? std::byteswap(raw) : raw;
}

}  // namespace

std::span<const AxisSignalDef> axisSignals() { return kSignals; }

const AxisSignalDef* findAxisSignal(std::string_view name) {
  if (name == "Status_WarningCode") name = "Status_AlarmCode";
  for (const auto& s : kSignals)
    if (s.name == name) return &s;
  return nullptr;
}

MappingRuntime::WordWidths MappingRuntime::widths(TelegramId t, Dir d) {
  WordWidths w;
  const auto defs = drives::words(t, d);
  for (size_t i = 0; i < defs.size(); ++i) w.wide[i] = wireBytes(defs[i].type) == 4;
  w.count = defs.size();
  return w;
}

MappingRuntime::MappingRuntime(const MappingSpec& spec)
    : spec_(&spec),
      swap_(spec.order != telegram(spec.telegram).order),
      toDrive_(widths(spec.telegram, Dir::ToDrive)),
      fromDrive_(widths(spec.telegram, Dir::FromDrive)) {
  const auto defs = drives::words(spec.telegram, Dir::FromDrive);
  for (const InputRule& r : spec.inputs) {
    const bool identity = r.scale.num == 1 && r.scale.den == 1 && r.scale.offset == 0;
    InputPlan d{1u << r.at.word, defs[r.at.word].type, identity};
    // A word rule whose sign comes from a status bit also depends on that bit's word.
    for (const InputRule& by : spec.inputs)
      if (r.signedBy >= 0 && by.signal == static_cast<AxisSignal>(r.signedBy)) d.words |= 1u << by.at.word;
    inputs_.push_back(d);
  }
}

void MappingRuntime::pack(const AxisSignalValues& values, RawWords& words) {
  words.fill(0);
  bool pulsed = false;
  const auto defs = drives::words(spec_->telegram, Dir::ToDrive);
  for (const OutputRule& r : spec_->outputs) {
    uint32_t& w = words[r.at.word];
    const auto sig = static_cast<size_t>(r.signal);
    switch (r.kind) {
      case OutputRule::Kind::Bit: {
        bool v = values[sig] != 0;
        if (r.zeroBeforeOne) {  // the first frame after start-up carries 0
          v = v && seenZero_[sig];
          seenZero_[sig] = true;
        }
        if (r.pulseRising) {
          const bool edge = v && !previous_[sig];
          previous_[sig] = v;
          v = edge;
          pulsed = pulsed || edge;
        }
        put(w, r.at, (v != r.invert) ? 1u : 0u);
        break;
      }
      case OutputRule::Kind::Field: {
        uint32_t code = r.value;
        for (uint8_t i = 0; i < r.codeCount; ++i)
          if (values[static_cast<size_t>(r.codeSignals[i])] != 0) {
            code = r.codes[i];
            break;
          }
        put(w, r.at, code);
        break;
      }
      case OutputRule::Kind::Word: {
        double x = values[sig];
        if (r.signedFrom >= 0 && values[static_cast<size_t>(r.signedFrom)] != 0) x = -x;
        const double scaled = x * r.scale.num / r.scale.den + r.scale.offset;
        const WireType type = defs[r.at.word].type;
        if (type == WireType::F32 && r.at.width == 0) {
          w = rawFromReal(scaled < r.lo ? r.lo : scaled > r.hi ? r.hi : scaled);
          break;
        }
        const auto raw = roundSaturate(scaled, static_cast<int64_t>(r.lo), static_cast<int64_t>(r.hi));
        if (r.at.width == 0) w = rawFromInt(type, raw);
        else put(w, r.at, static_cast<uint32_t>(raw));
        break;
      }
      case OutputRule::Kind::Const:
        if (r.at.width == 0) w = r.value;
        else put(w, r.at, r.value);
        break;
    }
  }
  // The first frame differs from the second only by the zero-before-one bits; a pulse that
  // fired drops in the next frame.
  repeatable_ = packed_ && !pulsed;
  packed_ = true;
  advanceSignOfLife(words);
}

uint32_t MappingRuntime::advanceSignOfLife(RawWords& words) {
  if (!spec_->masterSignOfLife) return 0;
  signOfLife_ = static_cast<uint8_t>(signOfLife_ % 15 + 1);  // 1..15, 0 skipped (spec B.6)
  put(words[spec_->masterSignOfLife->word], *spec_->masterSignOfLife, signOfLife_);
  return 1u << spec_->masterSignOfLife->word;
}

void MappingRuntime::unpack(const RawWords& words, AxisSignalValues& values) const { unpack(words, values, ~0u); }

void MappingRuntime::unpack(const RawWords& words, AxisSignalValues& values, uint32_t changedWords) const {
  // Bits first (the parser orders them so), so a word rule can take its sign from a bit.
  for (size_t i = 0; i < inputs_.size(); ++i) {
    if (!(inputs_[i].words & changedWords)) continue;
    const InputRule& r = spec_->inputs[i];
    const uint32_t w = words[r.at.word];
    double& out = values[static_cast<size_t>(r.signal)];
    if (r.kind == InputRule::Kind::Bit) {
      out = ((get(w, r.at) != 0) != r.invert) ? 1 : 0;
      continue;
    }
    const WireType type = inputs_[i].type;
    double raw;
    if (r.at.width != 0) raw = get(w, r.at);
    else if (type == WireType::F32) raw = realValue(w);
    else raw = static_cast<double>(signedValue(type, w));
    double x = inputs_[i].identity ? raw : (raw - r.scale.offset) * r.scale.den / r.scale.num;
    if (r.signedBy >= 0 && values[static_cast<size_t>(r.signedBy)] == 0) x = -x;
    out = x;
  }
}

void MappingRuntime::toWire(const RawWords& words, std::span<uint8_t> image) const {
  const auto defs = drives::words(spec_->telegram, Dir::ToDrive);
  for (size_t i = 0; i < defs.size(); ++i) writeWire(image, defs[i].offset, defs[i].type, spec_->order, words[i]);
}

void MappingRuntime::toDrive(const RawWords& words, RawWords& rx, uint32_t changedWords) const {
  for (uint32_t m = changedWords & ((1u << toDrive_.count) - 1u); m != 0; m &= m - 1) {
    const auto i = static_cast<size_t>(std::countr_zero(m));
    rx[i] = overTheWire(words[i], toDrive_.wide[i], swap_);
  }
}

void MappingRuntime::fromWire(std::span<const uint8_t> image, RawWords& words) const {
  const auto defs = drives::words(spec_->telegram, Dir::FromDrive);
  for (size_t i = 0; i < defs.size(); ++i) words[i] = readWire(image, defs[i].offset, defs[i].type, spec_->order);
}

uint32_t MappingRuntime::fromDrive(const RawWords& tx, RawWords& words) const {
  uint32_t changed = 0;
  for (size_t i = 0; i < fromDrive_.count; ++i) {
    const uint32_t w = overTheWire(tx[i], fromDrive_.wide[i], swap_);
    changed |= static_cast<uint32_t>(w != words[i]) << i;
    words[i] = w;
  }
  return changed;
}

}  // namespace virtcom::drives

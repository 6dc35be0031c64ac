// MappingRuntime: applies a validated mapping between UNIVERSAL_AXIS signals and raw telegram
// words every tick (no allocation, no lookups), and the signal table.
#include "drives/axis_mapping.hpp"

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

}  // namespace

std::span<const AxisSignalDef> axisSignals() { return kSignals; }

const AxisSignalDef* findAxisSignal(std::string_view name) {
  if (name == "Status_WarningCode") name = "Status_AlarmCode";
  for (const auto& s : kSignals)
    if (s.name == name) return &s;
  return nullptr;
}

void MappingRuntime::pack(const AxisSignalValues& values, RawWords& words) {
  words.fill(0);
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
  if (spec_->masterSignOfLife) {
    signOfLife_ = static_cast<uint8_t>(signOfLife_ % 15 + 1);  // 1..15, 0 skipped (spec B.6)
    put(words[spec_->masterSignOfLife->word], *spec_->masterSignOfLife, signOfLife_);
  }
}

void MappingRuntime::unpack(const RawWords& words, AxisSignalValues& values) const {
  const auto defs = drives::words(spec_->telegram, Dir::FromDrive);
  // Bits first (the parser orders them so), so a word rule can take its sign from a bit.
  for (const InputRule& r : spec_->inputs) {
    const uint32_t w = words[r.at.word];
    double& out = values[static_cast<size_t>(r.signal)];
    if (r.kind == InputRule::Kind::Bit) {
      out = ((get(w, r.at) != 0) != r.invert) ? 1 : 0;
      continue;
    }
    const WireType type = defs[r.at.word].type;
    double raw;
    if (r.at.width != 0) raw = get(w, r.at);
    else if (type == WireType::F32) raw = realValue(w);
    else raw = static_cast<double>(signedValue(type, w));
    double x = (raw - r.scale.offset) * r.scale.den / r.scale.num;
    if (r.signedBy >= 0 && values[static_cast<size_t>(r.signedBy)] == 0) x = -x;
    out = x;
  }
}

void MappingRuntime::toWire(const RawWords& words, std::span<uint8_t> image) const {
  const auto defs = drives::words(spec_->telegram, Dir::ToDrive);
  for (size_t i = 0; i < defs.size(); ++i) writeWire(image, defs[i].offset, defs[i].type, spec_->order, words[i]);
}

void MappingRuntime::fromWire(std::span<const uint8_t> image, RawWords& words) const {
  const auto defs = drives::words(spec_->telegram, Dir::FromDrive);
  for (size_t i = 0; i < defs.size(); ++i) words[i] = readWire(image, defs[i].offset, defs[i].type, spec_->order);
}

}  // namespace virtcom::drives

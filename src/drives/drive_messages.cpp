#include "drives/drive_messages.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>

namespace virtcom::drives {
namespace {

constexpr MessageDef kCatalogue[] = {
#define X(number, kind, reaction, effect, meaning) \
  {number, MessageKind::kind, Reaction::reaction, StatusEffect::effect, meaning},
#include "drives/drive_messages.def"
#undef X
};

constexpr PowerFlexFaultDef kPowerFlexFaults[] = {
#define X(number, meaning) {number, meaning},
#include "drives/powerflex_faults.def"
#undef X
};

int reactionRank(Reaction r) {
  switch (r) {
    case Reaction::Off2: return 3;
    case Reaction::Off3: return 2;
    case Reaction::Off1: return 1;
    case Reaction::None: return 0;
  }
  return 0;
}

}  // namespace

std::span<const MessageDef> messageCatalogue() { return kCatalogue; }

const MessageDef* findMessage(MessageKind kind, uint16_t number) {
  for (const MessageDef& m : kCatalogue)
    if (m.kind == kind && m.number == number) return &m;
  return nullptr;
}

std::span<const PowerFlexFaultDef> powerFlexFaults() { return kPowerFlexFaults; }

const PowerFlexFaultDef* findPowerFlexFault(uint16_t number) {
  for (const PowerFlexFaultDef& f : kPowerFlexFaults)
    if (f.number == number) return &f;
  return nullptr;
}

std::string messageName(MessageKind kind, uint16_t number) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%c%05u", kind == MessageKind::Fault ? 'F' : 'A', static_cast<unsigned>(number));
  return buf;
}

namespace {

std::expected<InjectableMessage, std::string> sinamicsCode(const std::string& text) {
  const bool wellFormed = text.size() >= 2 && (text[0] == 'F' || text[0] == 'A') && text.size() <= 6 &&
                          std::all_of(text.begin() + 1, text.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
  const MessageDef* found = nullptr;
  if (wellFormed) found = findMessage(text[0] == 'F' ? MessageKind::Fault : MessageKind::Alarm,
                                      static_cast<uint16_t>(std::stoul(text.substr(1))));
  if (found) return InjectableMessage{found->kind, found->number, found->reaction};
  std::string known;
  for (const MessageDef& m : kCatalogue) known += (known.empty() ? "" : ", ") + messageName(m.kind, m.number);
  return std::unexpected("'" + text + "' is not a known SINAMICS fault or alarm (expected one of: " + known + ")");
}

std::expected<InjectableMessage, std::string> powerFlexCode(const std::string& text) {
  std::string digits = text;
  if (!digits.empty() && digits[0] == 'F') digits.erase(0, 1);
  const bool numeric = !digits.empty() && digits.size() <= 3 &&
                       std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; });
  if (numeric && findPowerFlexFault(static_cast<uint16_t>(std::stoi(digits))))
    return InjectableMessage{MessageKind::Fault, static_cast<uint16_t>(std::stoi(digits)), Reaction::None};
  std::string known;
  for (const PowerFlexFaultDef& f : kPowerFlexFaults) known += (known.empty() ? "" : ", ") + std::to_string(f.number);
  return std::unexpected("'" + text + "' is not a PowerFlex fault number (expected F and one of: " + known + ")");
}

}  // namespace

std::expected<InjectableMessage, std::string> parseInjectionCode(MessageFamily family, const std::string& text) {
  return family == MessageFamily::PowerFlex ? powerFlexCode(text) : sinamicsCode(text);
}

bool FaultBuffer::raise(uint16_t number, int32_t value, Reaction reaction, int64_t nowNs) {
  for (size_t i = 0; i < count_; ++i)
    if (slots_[i].number == number) {
      slots_[i].causeActive = true;
      return false;
    }
  const size_t index = count_ < kSlots ? count_++ : kSlots - 1;
  slots_[index] = DriveMessage{number, value, nowNs, -1, reaction, true};
  return true;
}

void FaultBuffer::causeGone(uint16_t number) {
  for (size_t i = 0; i < count_; ++i)
    if (slots_[i].number == number) slots_[i].causeActive = false;
}

bool FaultBuffer::acknowledge(int64_t nowNs) {
  std::array<DriveMessage, kSlots> removed{}, kept{};
  size_t nRemoved = 0, nKept = 0;
  for (size_t i = 0; i < count_; ++i) {
    if (slots_[i].causeActive) {
      kept[nKept++] = slots_[i];
    } else {
      removed[nRemoved] = slots_[i];
      removed[nRemoved++].removedNs = nowNs;
    }
  }
  if (nRemoved == 0) return false;
  pushIncident(removed);
  for (size_t i = 0; i < kSlots; ++i) slots_[i] = i < nKept ? kept[i] : DriveMessage{};
  count_ = nKept;
  return true;
}

void FaultBuffer::pushIncident(const std::array<DriveMessage, kSlots>& incident) {
  // History incidents shift one block of 8 towards the end; the oldest drops out.
  std::copy_backward(slots_.begin() + kSlots, slots_.end() - kSlots, slots_.end());
  std::copy(incident.begin(), incident.end(), slots_.begin() + kSlots);
}

Reaction FaultBuffer::reaction() const {
  Reaction r = Reaction::None;
  for (size_t i = 0; i < count_; ++i)
    if (reactionRank(slots_[i].reaction) > reactionRank(r)) r = slots_[i].reaction;
  return r;
}

bool AlarmBuffer::isActive(uint16_t number) const {
  for (size_t i = 0; i < count_; ++i)
    if (slots_[i].number == number) return true;
  return false;
}

bool AlarmBuffer::raise(uint16_t number, int32_t value, int64_t nowNs) {
  if (isActive(number)) return false;
  const size_t index = count_ < kSlots ? count_++ : kSlots - 1;
  slots_[index] = DriveMessage{number, value, nowNs, -1, Reaction::None, true};
  return true;
}

void AlarmBuffer::clear(uint16_t number, int64_t nowNs) {
  for (size_t i = 0; i < count_; ++i) {
    if (slots_[i].number != number) continue;
    DriveMessage gone = slots_[i];
    gone.removedNs = nowNs;
    gone.causeActive = false;
    std::copy(slots_.begin() + static_cast<long>(i) + 1, slots_.begin() + static_cast<long>(count_), slots_.begin() + static_cast<long>(i));
    slots_[--count_] = DriveMessage{};
    std::copy_backward(slots_.begin() + kSlots, slots_.end() - 1, slots_.end());
    slots_[kSlots] = gone;
    return;
  }
}

uint16_t AlarmBuffer::latestNumber() const {
  size_t best = kSize;
  for (size_t i = 0; i < count_; ++i)
    if (best == kSize || slots_[i].raisedNs >= slots_[best].raisedNs) best = i;
  return best == kSize ? 0 : slots_[best].number;
}

}  // namespace virtcom::drives

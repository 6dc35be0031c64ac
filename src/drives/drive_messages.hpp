#pragma once
// The SINAMICS message catalogue (drive_messages.def) and the fault/alarm buffers of
// docs/drive-simulators.md (Faults and alarms). Buffers are fixed-size arrays: raising, clearing
// and acknowledging never allocate, so they run on the per-tick path.
#include <array>
#include <cstdint>
#include <expected>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace virtcom::drives {

enum class MessageKind : uint8_t { Fault, Alarm };
enum class Reaction : uint8_t { None, Off1, Off2, Off3 };
enum class StatusEffect : uint8_t { None, MotorTemp, PowerUnitTemp };

struct MessageDef {
  uint16_t number;
  MessageKind kind;
  Reaction reaction;
  StatusEffect effect;
  std::string_view meaning;
};

std::span<const MessageDef> messageCatalogue();
const MessageDef* findMessage(MessageKind kind, uint16_t number);
// "F07900" for (Fault, 7900).
std::string messageName(MessageKind kind, uint16_t number);

// PowerFlex fault numbers (powerflex_faults.def), decimal as transmitted.
struct PowerFlexFaultDef {
  uint16_t number;
  std::string_view meaning;
};
std::span<const PowerFlexFaultDef> powerFlexFaults();
const PowerFlexFaultDef* findPowerFlexFault(uint16_t number);

// Whose codes a drive accepts for injection (the cell file's `faults: inject: [{code: ...}]`).
enum class MessageFamily : uint8_t { Sinamics, PowerFlex };
struct InjectableMessage {
  MessageKind kind = MessageKind::Fault;
  uint16_t number = 0;
  Reaction reaction = Reaction::None;
};
// A code of `family` as the message it raises: SINAMICS "F07900" / "A01920" from the catalogue
// (with its reaction); PowerFlex "F4" or "4" from powerflex_faults.def (a fault, no reaction).
// Error text naming the expected form and the known codes if the text is not one.
std::expected<InjectableMessage, std::string> parseInjectionCode(MessageFamily family, const std::string& text);

struct DriveMessage {
  uint16_t number = 0;       // 0 = empty slot
  int32_t value = 0;
  int64_t raisedNs = 0;
  int64_t removedNs = -1;    // -1 while active
  Reaction reaction = Reaction::None;
  bool causeActive = false;  // the condition that raised it is still present
};

// Fault buffer r0945-style: indices 0..7 the current incident in order of arrival, 8..63 the
// seven previous incidents, most recent first. A 9th fault overwrites index 7.
class FaultBuffer {
 public:
  static constexpr size_t kSlots = 8;
  static constexpr size_t kSize = 64;

  // Raises `number` (already active: only its cause is renewed). Returns true if it was new.
  bool raise(uint16_t number, int32_t value, Reaction reaction, int64_t nowNs);
  // The cause of `number` disappeared (the fault stays until acknowledged).
  void causeGone(uint16_t number);
  // Acknowledge (caller detects the 0->1 edge): faults whose cause has gone are removed; the
  // removed ones move to history as one incident. Returns true if any fault was removed.
  bool acknowledge(int64_t nowNs);
  bool active() const { return count_ > 0; }
  size_t activeCount() const { return count_; }
  // Number of the fault at index 0, 0 if none (FAULT_CODE: docs/drive-simulators.md, Faults and
  // alarms).
  uint16_t firstNumber() const { return count_ ? slots_[0].number : 0; }
  // Strongest reaction among active faults (OFF2 > OFF3 > OFF1 > none).
  Reaction reaction() const;
  // Entry i of the r0945-style view (0..63); empty slots have number 0.
  const DriveMessage& entry(size_t i) const { return slots_[i]; }

 private:
  void pushIncident(const std::array<DriveMessage, kSlots>& incident);
  std::array<DriveMessage, kSize> slots_{};
  size_t count_ = 0;
};

// Alarm buffer: indices 0..7 active alarms by arrival (a 9th overwrites index 7), 8..63 the
// history of cleared alarms, most recently cleared at index 8. No acknowledge: an alarm goes
// when its cause goes.
class AlarmBuffer {
 public:
  static constexpr size_t kSlots = 8;
  static constexpr size_t kSize = 64;

  bool raise(uint16_t number, int32_t value, int64_t nowNs);
  void clear(uint16_t number, int64_t nowNs);
  bool active() const { return count_ > 0; }
  bool isActive(uint16_t number) const;
  size_t activeCount() const { return count_; }
  // Most recently raised active alarm, 0 if none (WARN_CODE).
  uint16_t latestNumber() const;
  const DriveMessage& entry(size_t i) const { return slots_[i]; }

 private:
  std::array<DriveMessage, kSize> slots_{};
  size_t count_ = 0;
};

}  // namespace virtcom::drives

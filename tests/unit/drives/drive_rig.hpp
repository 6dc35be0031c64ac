#pragma once
// Test rig for the drive simulators: a drive built from parameters (no cell file), fed raw
// telegram words one bus cycle at a time in virtual time, as a PLC would.
#include <cstdint>
#include <memory>
#include <vector>

#include "drives/normalisation.hpp"
#include "drives/powerflex.hpp"
#include "drives/speed_axis.hpp"

namespace virtcom::drives {

inline constexpr int64_t kBusCycleNs = 2'000'000;  // 2 ms PROFINET/EtherNet/IP cycle

template <typename Drive>
struct DriveRig {
  std::unique_ptr<Drive> drive;
  int64_t nowNs = 0;

  // Sends the same words for `cycles` bus cycles.
  void send(std::vector<uint32_t> words, int cycles = 1) {
    for (int i = 0; i < cycles; ++i) {
      nowNs += kBusCycleNs;
      drive->exchange(words, nowNs);
    }
  }
  void sendFor(std::vector<uint32_t> words, int64_t ms) { send(std::move(words), static_cast<int>(ms * 1'000'000 / kBusCycleNs)); }
  // No frames for `ms` milliseconds.
  void silence(int64_t ms) {
    for (int64_t i = 0; i < ms * 1'000'000 / kBusCycleNs; ++i) {
      nowNs += kBusCycleNs;
      drive->exchange({}, nowNs);
    }
  }
  uint32_t tx(size_t i) const { return drive->tx()[i]; }
};

struct SpeedRig : DriveRig<SpeedAxis> {
  explicit SpeedRig(TelegramId telegram = TelegramId::Std1, SpeedAxisParams p = {}) {
    DriveCommon c;
    c.telegram = telegram;
    drive = std::make_unique<SpeedAxis>("G120", c, p);
    drive->exchange({}, 0);  // power-up: the first reply
  }
  void stw(uint16_t stw1, int16_t nsoll = 0, int cycles = 1) { send({stw1, rawFromInt(WireType::I16, nsoll)}, cycles); }
  void stw352(uint16_t stw1, int16_t nsoll, int cycles = 1) {
    send({stw1, rawFromInt(WireType::I16, nsoll), 0, 0, 0, 0}, cycles);
  }
  uint16_t zsw1() const { return static_cast<uint16_t>(tx(0)); }
  uint16_t state() const { return zsw1() & 0x7F; }
  int16_t nist() const { return static_cast<int16_t>(signedValue(WireType::I16, tx(1))); }
  // Power-up sequence: ON = 0 first (S1 -> S2), then run with the setpoint until settled.
  void runAt(int16_t nsoll, uint16_t stwRun = 0x047F) {
    stw(0x047E, 0, 2);
    stw(stwRun, nsoll, 1500);  // 3 s: ramp (<= 2 s) and settling
  }
};

struct PowerFlexRig : DriveRig<PowerFlex> {
  explicit PowerFlexRig(TelegramId telegram = TelegramId::Pf525, PowerFlexParams p = {}) {
    DriveCommon c;
    c.telegram = telegram;
    drive = std::make_unique<PowerFlex>("PF", telegram == TelegramId::Pf525 ? "powerflex525" : "powerflex750", c, p);
    drive->exchange({}, 0);
  }
  void cmd(uint16_t logic, int16_t freq, int cycles = 1) { send({logic, rawFromInt(WireType::I16, freq)}, cycles); }
  uint16_t status() const { return static_cast<uint16_t>(tx(0)); }
  int16_t outputFreq() const { return static_cast<int16_t>(signedValue(WireType::I16, tx(1))); }
};

}  // namespace virtcom::drives

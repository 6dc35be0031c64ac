#pragma once
// Test rig for the EPos positioning axis: telegram 111 words sent one 2 ms bus cycle at a time,
// replies read back as raw words (docs/drives.md, Siemens Standard Telegram 111).
#include <functional>

#include "drive_rig.hpp"
#include "drives/epos_axis.hpp"

namespace virtcom::drives {

struct EposCommand {
  uint16_t stw1 = 0x043E;  // bits 1-5 and 10: no OFF2/OFF3, enable, no reject, no stop, control by PLC
  uint16_t posStw1 = 0;
  uint16_t posStw2 = 0;
  uint16_t stw2 = 0;
  uint16_t override = 0x4000;
  int32_t tarpos = 0;
  int32_t velocity = 100;  // 1000 LU/min
  uint16_t acc = 0x4000, dec = 0x4000;
};

struct EposRig : DriveRig<EposAxis> {
  EposCommand cmd;

  explicit EposRig(EposParams p = {}) {
    DriveCommon c;
    c.telegram = TelegramId::Std111;
    drive = std::make_unique<EposAxis>("S120", c, p);
    drive->exchange({}, 0);
  }
  void sendCmd(int cycles = 1) {
    send({cmd.stw1, cmd.posStw1, cmd.posStw2, cmd.stw2, cmd.override, static_cast<uint32_t>(cmd.tarpos),
          static_cast<uint32_t>(cmd.velocity), cmd.acc, cmd.dec, 0},
         cycles);
  }
  // OFF1 first (S1 -> S2), then ON: S4 with every enable.
  void powerUp() {
    cmd.stw1 = 0x043E;
    sendCmd(2);
    cmd.stw1 = 0x043F;
    sendCmd(2);
  }
  // Sends the current command until `done` holds (true) or `maxMs` pass (false).
  bool runUntil(const std::function<bool()>& done, int64_t maxMs) {
    for (int64_t t = 0; t < maxMs; t += 2) {
      sendCmd();
      if (done()) return true;
    }
    return false;
  }
  // One STW1.6 rising edge (the bit is cleared again afterwards).
  void activateTask() {
    cmd.stw1 = static_cast<uint16_t>(cmd.stw1 & ~0x40);
    sendCmd();
    cmd.stw1 |= 0x40;
    sendCmd();
    cmd.stw1 = static_cast<uint16_t>(cmd.stw1 & ~0x40);
  }
  uint16_t zsw1() const { return static_cast<uint16_t>(tx(0)); }
  uint16_t posZsw1() const { return static_cast<uint16_t>(tx(1)); }
  uint16_t posZsw2() const { return static_cast<uint16_t>(tx(2)); }
  uint16_t zsw2() const { return static_cast<uint16_t>(tx(3)); }
  uint16_t meldw() const { return static_cast<uint16_t>(tx(4)); }
  int32_t xist() const { return static_cast<int32_t>(tx(5)); }
  int32_t nistB() const { return static_cast<int32_t>(tx(6)); }
  uint16_t faultCode() const { return static_cast<uint16_t>(tx(7)); }
  uint16_t warnCode() const { return static_cast<uint16_t>(tx(8)); }
  bool zsw1Bit(int b) const { return (zsw1() >> b) & 1; }
  bool posZsw1Bit(int b) const { return (posZsw1() >> b) & 1; }
  bool posZsw2Bit(int b) const { return (posZsw2() >> b) & 1; }
  bool atRest() const { return zsw1Bit(13) && (posZsw2() & 0x30) == 0; }
};

}  // namespace virtcom::drives

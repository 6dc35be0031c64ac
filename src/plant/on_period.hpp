#pragma once
// The periods a device is on (a heater heating, a pump running, a valve open) as trace
// activities with their energy (power x duration), and the busy time for the device totals.
// Shared by the process devices; allocation-free per tick (trace appends excepted).
#include <cstdint>

#include "core/trace.hpp"

namespace virtcom::plant {

class OnPeriods {
 public:
  OnPeriods(double powerW) : powerW_(powerW) {}
  void prepare(Trace& trace, const char* label) { label_ = trace.internLabel(label); }
  // Called every tick with the device's state: opens an activity when it turns on, closes it
  // (with its energy) when it turns off.
  void update(Trace& trace, uint32_t device, bool on, int64_t nowNs) {
    if (on == on_) return;
    on_ = on;
    if (on) {
      startNs_ = nowNs;
      activity_ = trace.beginActivity(device, label_, nowNs);
      return;
    }
    busyNs_ += nowNs - startNs_;
    trace.endActivity(activity_, nowNs, powerW_ * static_cast<double>(nowNs - startNs_) * 1e-9);
  }
  // Busy time and energy up to endNs into the device's totals.
  void finish(Trace& trace, uint32_t device, int64_t endNs) const {
    DeviceTotals& t = trace.totals[device];
    t.busyNs = busyNs_ + (on_ ? endNs - startNs_ : 0);
    t.energyJ = powerW_ * static_cast<double>(t.busyNs) * 1e-9;
  }

 private:
  double powerW_ = 0;
  uint32_t label_ = 0, activity_ = 0;
  bool on_ = false;
  int64_t startNs_ = 0, busyNs_ = 0;
};

}  // namespace virtcom::plant

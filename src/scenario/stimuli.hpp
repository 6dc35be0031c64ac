#pragma once
// Applies a scenario's steps to the running cell (docs/scenarios.md "Steps"): before each scan of
// the soft PLC (sim::SimOptions::beforeScan), the steps that are due act once; forced variables
// are written again every scan; a pressed button goes back to FALSE at the first scan at or after
// its release time; a power loss stops the PLC with its memory back at its initial
// values (outputs off) and restarts it warm after its duration: initial values, then the RETAIN
// and PERSISTENT variables as they were when the power went. Everything is sized before the
// run: the scan path allocates nothing and looks nothing up.
#include <cstdint>
#include <span>
#include <vector>

#include "cell/cell.hpp"
#include "plc/runtime.hpp"
#include "scenario/plan.hpp"

namespace virtcom::scenario {

class Stimuli {
 public:
  // `plan` and `cell` must outlive it.
  Stimuli(const Plan& plan, cell::Cell& cell);

  // After the PLC's cold start, before its first scan: the scenario's `set:`.
  void preset(plc::Runtime& plc);
  // Before every scan: the steps due now (in file order), the PLC's restart, the forces.
  void beforeScan(plc::Runtime& plc);

 private:
  void apply(const Action& a, plc::Runtime& plc, int64_t nowNs);
  void powerDown(plc::Runtime& plc);
  void restart(plc::Runtime& plc);

  const Plan& plan_;
  cell::Cell& cell_;
  std::vector<uint8_t> stepDone_;
  std::vector<const Action*> forces_;  // capacity: every Force action of the plan
  struct Held {
    const Action* press = nullptr;
    int64_t releaseAtNs = 0;
  };
  std::vector<Held> held_;  // buttons pressed and not yet released; capacity: every Press action
  struct Retained {
    uint32_t address = 0;
    uint32_t size = 0;
  };
  std::vector<Retained> retained_;
  std::vector<uint8_t> retainedBytes_;  // their values when the power went
  int64_t restartAtNs_ = -1;            // the PLC is off until then (-1: on)
};

// Writes an action's value into the PLC's memory (and, for a located input, its input image);
// true if that changed the memory. Allocates nothing.
bool writeValue(const Action& a, plc::Runtime& plc);
// The same with the value's bytes given (a BOOL bit: its byte, masked by ref.bit).
bool writeBytes(const bc::VarRef& ref, std::span<const uint8_t> bytes, plc::Runtime& plc);

}  // namespace virtcom::scenario

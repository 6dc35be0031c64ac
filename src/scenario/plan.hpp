#pragma once
// A scenario bound to its loaded cell (docs/scenarios.md): the stimuli and faults on the time line
// or on conditions, and the assertions, every name resolved. Built by bindScenario(), applied by
// Stimuli (scenario/stimuli.hpp) and judged by Checker (scenario/checker.hpp).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "bytecode/module.hpp"
#include "plant/device.hpp"
#include "scenario/expression.hpp"
#include "scenario/link_loss.hpp"

namespace virtcom::scenario {

// One thing a step does to the running cell.
struct Action {
  enum class Kind : uint8_t { Set, Force, Release, ReleaseAll, Fact, Fault, PowerLoss, Parameter, Press };
  Kind kind = Kind::Set;
  std::string name;            // the variable, fact or device as written (messages)
  bc::VarRef ref;              // Set/Force/Release/Press: the PLC variable
  std::vector<uint8_t> bytes;  // Set/Force/Press: the value's bytes (a BOOL bit: its byte, masked by ref.bit)
  uint32_t index = 0;          // Fact: fact id; Fault, Parameter: device index in Cell::devices
  bool factValue = false;
  plant::FaultPlan plan;       // Fault: the device's plan from then on
  int64_t durationNs = 0;      // PowerLoss: how long the PLC stays off before its warm restart;
                               // Press: how long the button (a BOOL) is held TRUE
  std::unique_ptr<plant::Device> edited;  // Parameter: the device built with the new value, swapped in
};

// Actions applied once, before the scan of the first tick at or after `atNs`, or of the first
// tick in which `when` holds (one of the two).
struct Step {
  int64_t atNs = -1;
  Expression when;
  std::vector<Action> actions;
  SourceLocation loc;
};

struct Assertion {
  enum class Kind : uint8_t {
    At,           // `at: T, that: C`: C holds in the first tick at or after T
    Eventually,   // C holds in some tick of [from, from + within] (within: to the end)
    Always,       // C holds in every tick of [from, to]
    Never,        // C holds in no tick of [from, to]
    InOrder,      // each condition becomes true, in the order listed
    CycleTime,    // every completed cycle's time within [min, max]; at least one cycle
    Energy,       // a device's (or the cell's) energy within [min, max] joules
    NoCollision,  // no collision recorded
    PlcRunning,   // the PLC in RUN in every tick of [from, to]
    Final,        // C holds when the run ends
    RunEnd,       // the run ended this way (completed, time_limit, collision, ...)
  };
  Kind kind = Kind::At;
  SourceLocation loc;
  std::string what;                 // the assertion as the message quotes it
  std::vector<Expression> conditions;
  int64_t atNs = 0, fromNs = 0, toNs = INT64_MAX;
  double min = -1e300, max = 1e300;  // CycleTime in ns, Energy in J
  int device = -1;                   // Energy: index in Cell::devices, -1: all devices
  int runEnd = 0;                    // RunEnd: a virtcom::RunEnd value
};

struct Plan {
  std::vector<Action> presets;  // `set:` before the first scan
  std::vector<Step> steps;      // in file order
  std::vector<Assertion> assertions;
  std::vector<LinkLossWindow> linkLosses;  // `{link: plc, comm_loss: [...]}`: the external PLC's link cut
  std::string xfail;            // non-empty: the scenario is expected to fail, for this reason
  bool usesPlc = false;         // some step or condition touches the soft PLC
};

}  // namespace virtcom::scenario

#pragma once
// Finding the SFC steps of a compiled program, for tools that show which steps are active
// (`virtcom exec --trace-steps`, the HMI's SFC panel).
#include <cstdint>
#include <string>
#include <vector>

#include "bytecode/module.hpp"

namespace virtcom::sfc {

struct StepVariable {
  std::string path;        // "MAIN.Step2", "MAIN.fbFeeder.Wait"
  uint32_t activeAddress;  // the byte of its X flag in the PLC memory image
  uint32_t timeAddress;    // its T (TIME: 32-bit milliseconds in the step) in the image
};

// Every step of every chart reachable from the program instances, through FB instances (not
// through arrays), in declaration order. Allocates; call once after compiling. Empty if the
// program has no chart.
std::vector<StepVariable> findSteps(const bc::Module& module);

// The paths of the steps whose X flag is set in `memory`, separated by single spaces ("" if
// none). Appends to `out`, which it clears first; allocates only when `out` must grow.
void formatActiveSteps(const std::vector<StepVariable>& steps, const uint8_t* memory, std::string& out);

}  // namespace virtcom::sfc

#pragma once
// Reads a scenario's sections against its loaded cell (docs/scenarios.md): the run settings it
// overrides (time_limit, cycles, stop_on_*), `set:`, `faults:` (into the devices' plans),
// `steps:`, `expect:` and `xfail:`. Every mistake is a diagnostic at its file:line:col (C0xx).
#include "cell/cell.hpp"
#include "core/config_node.hpp"
#include "scenario/plan.hpp"

namespace virtcom::scenario {

// What a scenario runs: a cell file, or a PLC program alone (`program:`: a cell with no devices,
// no world and no cycle, where the keys about them are mistakes, reported as such).
enum class Controlled { Cell, ProgramAlone };

// `top` is the scenario's top-level map with `cell:` or `program:` (and `name:`, `description:`)
// already read; rejects unknown keys at the end. Changes `cell`'s run settings and device fault
// plans.
Plan bindScenario(ConfigReader& top, cell::Cell& cell, Controlled controlled);

// "100.25 s": a virtual time for messages, to the nanosecond without trailing zeros.
std::string formatSeconds(int64_t ns);

}  // namespace virtcom::scenario

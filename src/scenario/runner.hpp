#pragma once
// Running one scenario case (a file, or one row of its `parameters:` table): load its cell, bind
// the scenario, run the simulation (`sim::Simulation`, the same engine as `virtcom run`) with the
// scenario's stimuli before each scan and its checker among the trace sinks, and judge it.
// Deterministic: a case's verdict and trace depend on its files only, never on other cases
// running beside it (each has its own cell, PLC and clock).
#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "cell/cell.hpp"
#include "sim/simulation.hpp"

namespace virtcom::scenario {

struct CaseSpec {
  std::string file;           // the scenario file
  size_t row = SIZE_MAX;      // its parameter row, SIZE_MAX: none
  std::string name;           // "press error[code=90]"
  std::string classname;      // the file's path with dots: "examples.gearbox-cell.tests.press_error"
};

// Where a caller joins every case's run, on the case's worker thread (e.g. the PLC backend's
// machine code, the bridge to an external PLC, a PLC code coverage recorder per case, merged
// after all ran): `beforeRun` may add hooks, sinks, bridges and compiled code to the options and
// returns what must live as long as the run (e.g. a background compile, a bridge; may be null),
// or sets `error` (the case is then an ERROR, not run); `afterRun` sees the finished simulation.
// Both must be safe to call from several threads at once.
struct CaseHooks {
  std::function<std::shared_ptr<void>(cell::Cell& cell, const SourceManager& sources, sim::SimOptions& options, std::string& error)>
      beforeRun;
  std::function<void(sim::Simulation& simulation)> afterRun;
};

struct CaseOptions {
  bool keepFailedCell = false;  // keep the finished cell (trace with every change) of a failed case
  st::CompileOptions plc;       // how the cell's PLC program is compiled (e.g. with coverage probes)
  CaseHooks hooks;
};

enum class Verdict { Pass, Fail, Error, ExpectedFail, UnexpectedPass };
const char* verdictName(Verdict v);  // PASS, FAIL, ERROR, XFAIL, XPASS
bool verdictFails(Verdict v);        // FAIL, ERROR and XPASS fail a suite

struct CaseResult {
  CaseSpec spec;
  Verdict verdict = Verdict::Error;
  // FAIL, XFAIL: one line per failed assertion, "file:line: ASSERTION: at T: why (values)";
  // ERROR: the rendered diagnostics; XPASS: why it was expected to fail.
  std::vector<std::string> messages;
  std::string runEnd;           // how the run ended ("completed: 1 cycle(s) completed")
  int64_t virtualNs = 0;        // the run's virtual time
  int64_t wallNs = 0;           // how long it took (JUnit's time)
  std::unique_ptr<cell::Cell> cell;  // CaseOptions::keepFailedCell and the case failed
};

CaseResult runCase(const CaseSpec& spec, const CaseOptions& options);

}  // namespace virtcom::scenario

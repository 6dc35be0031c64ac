#pragma once
// Judges a scenario's assertions as its run goes (docs/scenarios.md "Assertions"): a TraceSink
// among the run's sinks, so it sees every tick (those event-driven time jumps over included, at
// their own times) once the tick's changes are on the bus, and the end. The conditions were bound
// before the run; per tick it evaluates them and keeps the first failure of each assertion,
// formatting its message only then.
#include <cstdint>
#include <string>
#include <vector>

#include "cell/cell.hpp"
#include "core/trace.hpp"
#include "plc/runtime.hpp"
#include "scenario/plan.hpp"

namespace virtcom::scenario {

// A failed assertion: where it is written, when it failed (virtual time) and why, with values.
struct Failure {
  size_t assertion = 0;  // index in Plan::assertions
  SourceLocation loc;
  int64_t timeNs = 0;
  std::string message;
};

class Checker final : public TraceSink {
 public:
  // `plan` and `cell` must outlive it.
  Checker(const Plan& plan, const cell::Cell& cell);
  // The running soft PLC (null without one): set once the simulation exists, before its run.
  void attach(const plc::Runtime* plc) { plc_ = plc; }

  void begin(const Trace& trace) override;
  void change(const SignalChange&) override {}
  void tick(const Trace& trace, int64_t nowNs) override;
  void end(const Trace& trace) override;

  // Every failed assertion, in file order; complete once end() was called.
  std::vector<Failure> failures() const;

 private:
  struct State {
    bool decided = false;
    bool failed = false;
    int64_t timeNs = 0;
    std::string message;
    std::vector<uint8_t> was;         // InOrder: each condition's value in the previous tick
    std::vector<int64_t> seenNs;      // InOrder: when each first became true, -1: not yet
  };
  void judgeTick(const Assertion& a, State& s, int64_t nowNs);
  void judgeOrder(const Assertion& a, State& s, int64_t nowNs);
  void judgeEnd(const Assertion& a, State& s, const Trace& trace);
  void fail(State& s, int64_t nowNs, std::string message);
  std::string values(const Expression& e) const;
  ValueSources sources() const;

  const Plan& plan_;
  const cell::Cell& cell_;
  const plc::Runtime* plc_ = nullptr;
  std::vector<State> states_;
};

}  // namespace virtcom::scenario

#pragma once
// How often activity-diagram rules fired in a run, read from the fired flags the lowering keeps
// in the program (lang/ad/lower.hpp, kFiredVariable) after every tick: the one counter behind the
// reports' rule tables (cli/rule_trace.hpp) and the web HMI's rule panel (hmi/live_state.hpp),
// so both give the same counts, in tick and in event-driven time.
#include <cstdint>
#include <vector>

#include "bytecode/module.hpp"
#include "plc/runtime.hpp"

namespace virtcom::plc {

// A rule's fired flag and the task that scans its diagram's PROGRAM.
struct CountedRule {
  bc::VarRef flag;
  uint32_t task = 0;
};

// The PLC scans in which a rule's IF held (and it wrote its THEN), and the virtual times of the
// first and the last of them (-1 while it never fired).
struct RuleFiring {
  uint64_t scans = 0;
  int64_t firstNs = -1;
  int64_t lastNs = -1;
};

// Whether the BOOL at `flag` (a bit, or a whole byte) is set in `memory`.
inline bool flagSet(const bc::VarRef& flag, const uint8_t* memory) {
  return flag.bit < 0 ? memory[flag.address] != 0 : ((memory[flag.address] >> flag.bit) & 1) != 0;
}

class RuleCounter {
 public:
  RuleCounter() = default;
  // `taskCount`: the module's tasks (every CountedRule::task is below it).
  RuleCounter(std::vector<CountedRule> rules, size_t taskCount);

  bool empty() const { return rules_.empty(); }

  // Call after every tick of `plc`: for each task that scanned in this tick (a skipped repeat
  // scan counts, it is the previous scan again), counts the rules of its diagrams whose fired
  // flag is set, at the tick's virtual time; scans that event-driven time jumped over since the
  // last call (single-task programs only) count as repeats of the last counted one. Allocates
  // nothing and looks nothing up.
  void count(const Runtime& plc);

  // Back to no firings, for a new run of a cold-started runtime (the HMI's reset).
  void restart();

  // One per rule, in the constructor's order.
  const std::vector<RuleFiring>& firings() const { return firings_; }

 private:
  struct Counted {
    CountedRule rule;
    bool lastSet = false;  // its flag after the last counted scan
  };
  std::vector<Counted> rules_;
  std::vector<RuleFiring> firings_;  // parallel to rules_
  std::vector<uint64_t> scansSeen_;  // per task: its scan count at the last count()
};

}  // namespace virtcom::plc

#pragma once
// What the activity-diagram rules do in a run, read from the fired flags the lowering keeps in
// the program (lang/ad/lower.hpp, kFiredVariable) after every scan, so no second runtime watches
// the rules:
// - `exec --trace-rules` and `run --trace-rules` print the rules that fired (RuleTracer);
// - `run --report` and `--json` show each diagram's tables with how often each rule fired
//   (RuleCounter);
// - the web HMI's rule panel counts them (findWatchedRules).
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "bytecode/module.hpp"
#include "lang/ad/rule_trace.hpp"
#include "plc/runtime.hpp"
#include "report/diagram_tables.hpp"

namespace virtcom::cli {

struct WatchedRule {
  ad::TracedRule rule;
  bc::VarRef flag;  // its fired flag
};

// The rules of every diagram file (.ad, .adxml) among `files`, found in the compiled module,
// in fired-flag order; empty without a diagram file. Nullopt (after a message on stderr) if a
// diagram file cannot be read.
std::optional<std::vector<WatchedRule>> findWatchedRules(const std::vector<std::string>& files, const bc::Module& module);

class RuleTracer {
 public:
  // The rules of every diagram file among `files`. Nullopt (after a message on stderr) if no
  // file is a diagram file.
  static std::optional<RuleTracer> load(const std::vector<std::string>& files, const bc::Module& module);

  // Prints `scan N  Diagram rule I fired: THEN` for every rule whose flag is set in `memory`.
  void print(uint64_t scan, const uint8_t* memory, std::ostream& out) const;

 private:
  struct Watched {
    std::string prefix;  // "Supply rule 3 fired: SupplyValve := FALSE, Filled := TRUE"
    bc::VarRef flag;     // its fired flag
  };
  std::vector<Watched> rules_;
};

class RuleCounter {
 public:
  // The LU and rule tables of every diagram file (.ad, .adxml) among `files` (none: empty), and
  // the fired flag and task of each rule in the compiled module. Nullopt (after a message on
  // stderr) if a diagram file cannot be read.
  static std::optional<RuleCounter> load(const std::vector<std::string>& files, const bc::Module& module);

  bool empty() const { return sections_.empty(); }

  // Call after every tick of `plc`: for each task that scanned in this tick (a skipped repeat
  // scan counts, it is the previous scan again), counts the rules of its diagrams whose fired
  // flag is set, at the tick's virtual time; scans that event-driven time jumped over since the
  // last call (single-task programs only) count as repeats of the last counted one. Allocates
  // nothing and looks nothing up.
  void count(const plc::Runtime& plc);

  // The tables with the counts so far, one section per diagram, in file and diagram order.
  const std::vector<report::DiagramTablesSection>& sections() const { return sections_; }

 private:
  struct Counted {
    bc::VarRef flag;
    uint32_t task = 0;    // the task that runs the diagram's PROGRAM
    uint32_t section = 0;
    uint32_t row = 0;     // of the section's rule table
    bool lastSet = false; // its flag after the last counted scan
  };
  std::vector<report::DiagramTablesSection> sections_;
  std::vector<Counted> rules_;
  std::vector<uint64_t> scansSeen_;  // per task of the module: its scan count at the last count()
};

}  // namespace virtcom::cli

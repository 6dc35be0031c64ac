#pragma once
// What the activity-diagram rules do in a run, read from the fired flags the lowering keeps in
// the program (lang/ad/lower.hpp, kFiredVariable) after every scan, so no second runtime watches
// the rules:
// - `exec --trace-rules` and `run --trace-rules` print the rules that fired (RuleTracer);
// - `run --report` and `--json` show each diagram's tables with how often each rule fired
//   (RuleTables, counting with plc::RuleCounter);
// - the web HMI's rule panel counts them with the same plc::RuleCounter (findWatchedRules).
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "bytecode/module.hpp"
#include "lang/ad/rule_trace.hpp"
#include "plc/rule_counter.hpp"
#include "plc/runtime.hpp"
#include "report/diagram_tables.hpp"

namespace virtcom::cli {

struct WatchedRule {
  ad::TracedRule rule;
  plc::CountedRule counted;  // its fired flag and the task scanning it
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

// Each diagram's LU and rule tables with how often each rule fired, for the run's reports.
class RuleTables {
 public:
  // The LU and rule tables of every diagram file (.ad, .adxml) among `files` (none: empty), and
  // the fired flag and task of each rule in the compiled module. Nullopt (after a message on
  // stderr) if a diagram file cannot be read.
  static std::optional<RuleTables> load(const std::vector<std::string>& files, const bc::Module& module);

  bool empty() const { return sections_.empty(); }

  // Call after every tick of `plc` (plc::RuleCounter::count: nothing allocated or looked up).
  void count(const plc::Runtime& plc) { counter_.count(plc); }
  // The counts start again at 0, for the next run of a reset (a cold-started runtime).
  void restart() { counter_.restart(); }

  // The tables with the counts so far, one section per diagram, in file and diagram order.
  std::vector<report::DiagramTablesSection> sections() const;

 private:
  struct Row {
    uint32_t section = 0;
    uint32_t row = 0;  // of the section's rule table
  };
  std::vector<report::DiagramTablesSection> sections_;  // counts all zero
  plc::RuleCounter counter_;
  std::vector<Row> rows_;  // parallel to the counter's rules
};

}  // namespace virtcom::cli

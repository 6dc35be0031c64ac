#pragma once
// The activity-diagram rules of a compiled program with their fired flags, read from the flags
// the lowering keeps in the program (lang/ad/lower.hpp), so no second runtime watches the rules:
// printed by `virtcom exec --trace-rules` and `run --trace-rules` after every scan, counted by
// the web HMI's rule panel.
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "bytecode/module.hpp"
#include "lang/ad/rule_trace.hpp"

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

}  // namespace virtcom::cli

#pragma once
// `virtcom exec --trace-rules` and `run --trace-rules`: after every scan, one line per activity-diagram rule whose IF
// held, read from the fired flags the lowering keeps in the program (lang/ad/lower.hpp), so no
// second runtime watches the rules.
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "bytecode/module.hpp"

namespace virtcom::cli {

class RuleTracer {
 public:
  // The rules of every diagram file (.ad, .adxml) among `files`, found in the compiled module.
  // Nullopt (after a message on stderr) if no file is a diagram file.
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

#pragma once
// What `--trace-rules` prints (and the HMI's rule panel shows) about a rule that fired: the rules of a program in the order of
// their fired flags (lower.hpp, kFiredVariable), each with its diagram, index and THEN.
#include <string>
#include <vector>

#include "lang/ad/diagram.hpp"

namespace virtcom::ad {

struct TracedRule {
  std::string diagram;  // "Supply"
  std::string index;    // "3", "2.1"
  std::string luType;   // its logic unit's type: "1", "2", "3", "4-1", "4-2"
  std::string then;     // "SupplyValve := FALSE, Filled := TRUE"; blocks: "React.IN := TRUE"
};

// Element k-1 describes the rule whose fired flag is __ad_fired[k]. Decomposes every diagram of
// a checked program; allocates.
std::vector<TracedRule> tracedRules(const Program& program);

}  // namespace virtcom::ad

#pragma once
// PLC code coverage as data (docs/coverage.md): one record per probe the compiler placed, with
// where it is in the source and how often it ran. The bytecode layer fills it from a program's
// counters (bytecode/coverage.hpp), report/ writes it (lcov, Cobertura, the terminal summary),
// and runs of the same or of different programs merge by adding counts.
#include <cstdint>
#include <string>
#include <vector>

namespace virtcom {

enum class CoverageKind : uint8_t {
  Statement,   // an ST statement began (counted by source line)
  Branch,      // an arm of an IF/ELSIF/ELSE or CASE was entered (arm: its index; the last arm
               // of a decision without ELSE is the implicit one: no condition held)
  Step,        // an SFC step became active
  Transition,  // an SFC transition fired
  Rule,        // an activity-diagram rule fired (its IF held in a scan)
};
const char* coverageKindName(CoverageKind k);  // "statement", "branch", "step", "transition", "rule"

struct CoveragePoint {
  std::string file;    // source path as compiled
  std::string pou;     // qualified POU name: "MAIN", "FB_Motor.Start"
  uint32_t line = 0;   // the statement's line; for a branch the line of its IF/CASE; for a rule
                       // the line of the arc to its first output (lang/ad/lower.hpp)
  uint32_t column = 0; // the statement's (IF/CASE's) column: tells decisions of one line apart
  CoverageKind kind = CoverageKind::Statement;
  uint32_t arm = 0;    // Branch: index of the arm in its decision
  uint32_t arms = 0;   // Branch: how many arms the decision has (implicit ELSE included)
  std::string name;    // Step, Transition: the element's name; Rule: its index ("3", "3.1")
  uint64_t count = 0;
};

// The coverage of one or more runs: points sorted by (file, line, column, kind, arm, name, pou).
class CoverageData {
 public:
  CoverageData() = default;
  explicit CoverageData(std::vector<CoveragePoint> points);

  // Adds `other`'s counts: a point both have (same file, POU, place, kind, arm, name) sums its
  // counts, any other point is taken over as it is. Commutative and associative, so runs merged
  // in any order (parallel scenarios) give the same data.
  void merge(const CoverageData& other);
  const std::vector<CoveragePoint>& points() const { return points_; }
  bool empty() const { return points_.empty(); }

 private:
  std::vector<CoveragePoint> points_;
};

// True if a and b are the same probe (every field but count equal).
bool sameCoveragePoint(const CoveragePoint& a, const CoveragePoint& b);

}  // namespace virtcom

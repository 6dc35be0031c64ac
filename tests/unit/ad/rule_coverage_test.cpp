// PLC code coverage of activity-diagram rules (docs/coverage.md, "What is counted"): each rule
// is a point at the line of the arc to its first output, counting the scans in which it fired,
// the same count as plc::RuleCounter's (the reports' rule tables), on the interpreter and the
// AOT backend alike; without coverage the program has neither probe nor the IF a rule that only
// drives blocks gets for its probe. The program is the scenario plan's signals.ad, whose counts
// its comments explain.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <tuple>

#include "ad_fixture.hpp"
#include "bytecode/coverage.hpp"
#include "lang/ad/lower.hpp"
#include "plc/rule_counter.hpp"
#include "support/read_file.hpp"

namespace virtcom::ad {
namespace {

namespace fs = std::filesystem;

const fs::path kSignals = fs::path(VIRTCOM_SOURCE_DIR) / "tests" / "e2e" / "data" / "scenarios" / "signals" / "signals.ad";

std::unique_ptr<bc::Module> compileSignals(bool coverage) {
  SourceManager sources;
  Diagnostics diags;
  std::vector<st::SourceInput> inputs{plcopen::sourceInput("signals.ad", virtcom::test::readFile(kSignals))};
  auto module = st::compileProgram(inputs, sources, diags, st::coverageOptions(coverage));
  EXPECT_NE(module, nullptr) << diags.render(sources);
  return module;
}

void set(const bc::Module& m, plc::Runtime& runtime, const std::string& name) {
  auto ref = bc::resolveVariable(m, "Signals." + name);
  ASSERT_TRUE(ref) << name;
  bc::writeValueFromText(m, *ref, "TRUE", runtime.machine().memory());
}

// halt.yaml on the bare runtime: Go set before the first scan, Halt before scan 51 (0.5 s),
// 101 scans of 10 ms (0 s to 1 s). `counter` (if given) counts the rules after every scan.
CoverageData runHalt(const bc::Module& m, bool native, plc::RuleCounter* counter = nullptr) {
  VirtualClock clock;
  plc::Runtime runtime(m, clock);
  if (native) {
    aot::CompileOptions options;
    options.cacheDir = VIRTCOM_AOT_TEST_CACHE;
    const aot::CompileResult compiled = aot::compileModule(m, options);
    EXPECT_TRUE(compiled.code) << compiled.error;
    runtime.machine().useCompiled(compiled.code);
  }
  EXPECT_TRUE(runtime.coldStart()) << runtime.faultText();
  set(m, runtime, "Go");
  for (int scan = 1; scan <= 101; ++scan) {
    if (scan == 51) set(m, runtime, "Halt");
    EXPECT_TRUE(runtime.tick()) << runtime.faultText();
    if (counter) counter->count(runtime);
  }
  return bc::collectCoverage(m, runtime.machine().memory());
}

std::vector<CoveragePoint> rulesOf(const CoverageData& data) {
  std::vector<CoveragePoint> rules;
  std::ranges::copy_if(data.points(), std::back_inserter(rules), [](const CoveragePoint& p) { return p.kind == CoverageKind::Rule; });
  return rules;
}

TEST(RuleCoverage, EachRuleCountsTheScansInWhichItFiredAtItsArc) {
  auto m = compileSignals(true);
  ASSERT_NE(m, nullptr);
  const CoverageData data = runHalt(*m, false);
  using Row = std::tuple<std::string, uint32_t, std::string, uint64_t>;  // POU, line, rule, count
  std::vector<Row> rules;
  for (const CoveragePoint& p : rulesOf(data)) {
    EXPECT_EQ(p.file, "signals.ad");
    rules.emplace_back(p.pou, p.line, p.name, p.count);
  }
  EXPECT_EQ(rules, (std::vector<Row>{{"Signals.Lights", 27, "1", 101},    // Start -> Delay: every scan
                                     {"Signals.Lights", 28, "2", 81},     // Delay -> GreenOn: from 0.2 s
                                     {"Signals.Stopping", 42, "1", 51},   // Both -> RedOn: from 0.5 s
                                     {"Signals.Alarm", 54, "1", 0}}));    // Never -> HornOn: never
  // Besides the rules only the PROGRAM's calls of its diagrams count, at the diagram lines; the
  // statements a rule is lowered to are no lines of their own.
  for (const CoveragePoint& p : data.points()) {
    if (p.kind == CoverageKind::Rule) continue;
    EXPECT_EQ(p.kind, CoverageKind::Statement) << p.line;
    EXPECT_EQ(p.pou, "Signals") << p.line;
    EXPECT_TRUE(p.line == 19 || p.line == 32 || p.line == 47) << p.line;
    EXPECT_EQ(p.count, 101u) << p.line;
  }
}

TEST(RuleCoverage, CountsAreTheRuleCountersOnBothBackends) {
  auto m = compileSignals(true);
  ASSERT_NE(m, nullptr);
  std::vector<plc::CountedRule> flags;
  for (int k = 1; k <= 4; ++k) {
    auto flag = bc::resolveVariable(*m, "Signals." + std::string(kFiredVariable) + "[" + std::to_string(k) + "]");
    ASSERT_TRUE(flag) << k;
    flags.push_back({*flag, 0});
  }
  plc::RuleCounter counter(flags, m->tasks.size());
  const std::vector<CoveragePoint> interpreted = rulesOf(runHalt(*m, false, &counter));
  ASSERT_EQ(interpreted.size(), counter.firings().size());
  for (size_t k = 0; k < interpreted.size(); ++k) EXPECT_EQ(interpreted[k].count, counter.firings()[k].scans) << "rule " << k + 1;
  const std::vector<CoveragePoint> native = rulesOf(runHalt(*m, true));
  ASSERT_EQ(native.size(), interpreted.size());
  for (size_t k = 0; k < native.size(); ++k) EXPECT_EQ(native[k].count, interpreted[k].count) << "rule " << k + 1;
}

// The conditional jumps in the code of the diagram's ACTION `name`.
size_t conditionalJumps(const bc::Module& m, const std::string& name) {
  auto pou = std::ranges::find_if(m.pous, [&](const bc::PouInfo& p) { return p.name == name; });
  EXPECT_NE(pou, m.pous.end()) << name;
  if (pou == m.pous.end()) return 0;
  return static_cast<size_t>(std::count_if(m.code.begin() + pou->codeStart, m.code.begin() + pou->codeStart + pou->codeSize,
                                           [](const bc::Instr& i) { return i.op == bc::Op::JZ || i.op == bc::Op::JNZ; }));
}

TEST(RuleCoverage, OffCompilesNeitherProbeNorTheIfOfARuleThatOnlyDrivesBlocks) {
  auto plain = compileSignals(false);
  auto covered = compileSignals(true);
  ASSERT_NE(plain, nullptr);
  ASSERT_NE(covered, nullptr);
  EXPECT_TRUE(plain->coverage.probes.empty());
  EXPECT_TRUE(std::ranges::none_of(plain->code, [](const bc::Instr& i) { return i.op == bc::Op::COVER; }));
  // Lights rule 1 drives the timer only: its `IF __ad_fired[1]` exists with coverage alone.
  EXPECT_EQ(conditionalJumps(*plain, "Signals.Lights"), 1u);
  EXPECT_EQ(conditionalJumps(*covered, "Signals.Lights"), 2u);
  EXPECT_EQ(conditionalJumps(*plain, "Signals.Stopping"), 1u);
  EXPECT_EQ(conditionalJumps(*covered, "Signals.Stopping"), 1u);
}

}  // namespace
}  // namespace virtcom::ad

// PLC code coverage end to end inside the process: hand-counted programs compiled with probes,
// run on the interpreter and on the AOT backend, collected, merged and written as lcov, whose
// every DA/BRDA line was counted by hand (programs/*.st say why each count is what it is).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "aot/compile.hpp"
#include "bytecode/coverage.hpp"
#include "bytecode/disassembler.hpp"
#include "core/clock.hpp"
#include "lang/st/compiler.hpp"
#include "plc/runtime.hpp"
#include "report/coverage.hpp"
#include "support/read_file.hpp"

namespace fs = std::filesystem;
using namespace virtcom;
using test::readFile;

namespace {

const fs::path kDir = fs::path(VIRTCOM_SOURCE_DIR) / "tests" / "unit" / "coverage" / "programs";

std::unique_ptr<bc::Module> compileHandCounted(bool coverage) {
  std::vector<st::SourceInput> inputs;
  for (const char* name : {"main.st", "chart.st"})
    inputs.push_back({std::string("programs/") + name, readFile(kDir / name)});
  SourceManager sources;
  Diagnostics diags;
  auto module = st::compileProgram(inputs, sources, diags, st::coverageOptions(coverage));
  EXPECT_NE(module, nullptr) << diags.render(sources);
  return module;
}

// Runs `scans` scans (on machine code when given) and collects the counters.
CoverageData run(const bc::Module& m, int scans, std::shared_ptr<const vm::CompiledCode> code = nullptr) {
  VirtualClock clock;
  plc::Runtime runtime(m, clock);
  if (code) runtime.machine().useCompiled(std::move(code));
  EXPECT_TRUE(runtime.coldStart()) << runtime.faultText();
  for (int k = 0; k < scans; ++k) EXPECT_TRUE(runtime.tick()) << runtime.faultText();
  return bc::collectCoverage(m, runtime.machine().memory());
}

void expectGolden(const std::string& text, const fs::path& golden) {
  if (std::getenv("VIRTCOM_UPDATE_GOLDEN")) std::ofstream(golden, std::ios::binary) << text;
  EXPECT_EQ(text, readFile(golden)) << "differs from " << golden << " (VIRTCOM_UPDATE_GOLDEN=1 rewrites it)";
}

TEST(Coverage, HandCountedProgramsGiveTheGoldenTracefile) {
  auto m = compileHandCounted(true);
  ASSERT_NE(m, nullptr);
  expectGolden(report::lcovTracefile(run(*m, 4), "hand"), kDir / "hand.info");
}

TEST(Coverage, SummaryCountsPerPou) {
  auto m = compileHandCounted(true);
  ASSERT_NE(m, nullptr);
  const std::vector<report::PouCoverage> rows = report::coverageByPou(run(*m, 4));
  ASSERT_EQ(rows.size(), 4u);  // Cell, Twice, MAIN, total
  const auto row = [&](const std::string& pou) {
    return *std::find_if(rows.begin(), rows.end(), [&](const report::PouCoverage& r) { return r.pou == pou; });
  };
  EXPECT_EQ(row("MAIN").lines.hit, 8u);
  EXPECT_EQ(row("MAIN").lines.total, 11u);  // the FALSE, `total := 0` and `total := -1` lines never ran
  EXPECT_EQ(row("MAIN").branches.hit, 4u);
  EXPECT_EQ(row("MAIN").branches.total, 7u);
  EXPECT_EQ(row("Cell").steps.hit, 2u);
  EXPECT_EQ(row("Cell").steps.total, 3u);
  EXPECT_EQ(row("Cell").transitions.hit, 2u);
  EXPECT_EQ(row("Cell").transitions.total, 4u);
  EXPECT_EQ(rows.back().pou, "total");
  EXPECT_EQ(rows.back().branches.total, 7u);
}

TEST(Coverage, MergingTwoRunsAddsTheirCounts) {
  auto m = compileHandCounted(true);
  ASSERT_NE(m, nullptr);
  CoverageData merged = run(*m, 1);
  merged.merge(run(*m, 3));
  const CoverageData four = run(*m, 4);
  ASSERT_EQ(merged.points().size(), four.points().size());
  // One scan plus three from a cold start: MAIN and Twice count what four scans do (their counts
  // do not depend on earlier scans); the chart restarts, so Idle is activated 1 + 2 times.
  for (size_t i = 0; i < four.points().size(); ++i) {
    const CoveragePoint& p = merged.points()[i];
    ASSERT_TRUE(sameCoveragePoint(p, four.points()[i]));
    if (p.pou != "Cell") {
      EXPECT_EQ(p.count, four.points()[i].count) << p.pou << " line " << p.line;
    } else if (p.kind == CoverageKind::Step && p.name == "Idle") {
      EXPECT_EQ(p.count, 3u);
    } else if (p.kind == CoverageKind::Step && p.name == "Work") {
      EXPECT_EQ(p.count, 1u);
    }
  }
  // Merging the same run twice doubles every count.
  CoverageData twice = four;
  twice.merge(four);
  for (size_t i = 0; i < four.points().size(); ++i) EXPECT_EQ(twice.points()[i].count, 2 * four.points()[i].count);
}

TEST(Coverage, CountersSurviveAColdStart) {
  auto m = compileHandCounted(true);
  ASSERT_NE(m, nullptr);
  VirtualClock clock;
  plc::Runtime runtime(*m, clock);
  ASSERT_TRUE(runtime.coldStart());
  ASSERT_TRUE(runtime.tick());
  ASSERT_TRUE(runtime.coldStart());  // a power loss: variables start again, counts go on
  ASSERT_TRUE(runtime.tick());
  const CoverageData data = bc::collectCoverage(*m, runtime.machine().memory());
  const auto first = std::find_if(data.points().begin(), data.points().end(), [](const CoveragePoint& p) {
    return p.pou == "MAIN" && p.kind == CoverageKind::Statement;
  });
  ASSERT_NE(first, data.points().end());
  EXPECT_EQ(first->count, 2u);
}

TEST(Coverage, InterpreterAndAotCountAlike) {
  auto m = compileHandCounted(true);
  ASSERT_NE(m, nullptr);
  aot::CompileOptions options;
  options.cacheDir = VIRTCOM_AOT_TEST_CACHE;
  const aot::CompileResult compiled = aot::compileModule(*m, options);
  ASSERT_TRUE(compiled.code) << compiled.error;
  const CoverageData interp = run(*m, 4), native = run(*m, 4, compiled.code);
  ASSERT_EQ(interp.points().size(), native.points().size());
  for (size_t i = 0; i < interp.points().size(); ++i) EXPECT_EQ(interp.points()[i].count, native.points()[i].count) << i;
  EXPECT_EQ(report::lcovTracefile(native, "hand"), report::lcovTracefile(interp, "hand"));
}

// Zero cost when off: without the option no probe, no counter, and the very same code.
TEST(Coverage, OffCompilesNoProbe) {
  auto off = compileHandCounted(false);
  auto on = compileHandCounted(true);
  ASSERT_NE(off, nullptr);
  ASSERT_NE(on, nullptr);
  EXPECT_TRUE(off->coverage.probes.empty());
  EXPECT_EQ(std::count_if(off->code.begin(), off->code.end(), [](const bc::Instr& i) { return i.op == bc::Op::COVER; }), 0);
  EXPECT_EQ(std::count_if(on->code.begin(), on->code.end(), [](const bc::Instr& i) { return i.op == bc::Op::COVER; }),
            static_cast<std::ptrdiff_t>(on->coverage.probes.size()));
  EXPECT_LT(off->staticSize, on->staticSize);
  EXPECT_TRUE(bc::collectCoverage(*off, std::vector<uint8_t>(off->memorySize()).data()).empty());
}

TEST(Coverage, DisassemblyNamesTheCounter) {
  auto on = compileHandCounted(true);
  ASSERT_NE(on, nullptr);
  const uint32_t pc = static_cast<uint32_t>(
      std::find_if(on->code.begin(), on->code.end(), [](const bc::Instr& i) { return i.op == bc::Op::COVER; }) -
      on->code.begin());
  EXPECT_EQ(bc::disassembleInstruction(*on, pc).substr(0, 9), "COVER    ");
  EXPECT_NE(bc::disassembleInstruction(*on, pc).find('#'), std::string::npos);
}

// Probes go after a decision's branch, never between the comparison and it, so the peephole
// pass still fuses them; the listing with probes is golden (reviewed by hand: a probe first in
// every statement and arm, the implicit ELSE's probe behind the THEN arm's jump).
TEST(Coverage, ProbesLeaveComparisonsFused) {
  SourceManager sources;
  Diagnostics diags;
  const std::string text =
      "PROGRAM MAIN\nVAR x, y : DINT; END_VAR\n"
      "IF x < 10 THEN y := 1; END_IF;\n"
      "CASE x OF 1: y := 10; 2..5: y := 20; END_CASE;\n"
      "END_PROGRAM\n";
  auto m = st::compileProgram({{"fused.st", text}}, sources, diags, st::coverageOptions(true));
  ASSERT_NE(m, nullptr) << diags.render(sources);
  std::string listing;
  for (uint32_t p = 0; p < m->pous.size(); ++p)
    if (m->pous[p].name == "MAIN") listing = bc::disassemble(*m, p);
  EXPECT_NE(listing.find("  JGEK "), std::string::npos) << listing;
  EXPECT_NE(listing.find("  JNEK "), std::string::npos) << listing;
  EXPECT_EQ(listing.find("  LTK "), std::string::npos) << listing;
  EXPECT_EQ(listing.find("  EQK "), std::string::npos) << listing;
  expectGolden(listing, kDir / "fused.listing");
}

}  // namespace

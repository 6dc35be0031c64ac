// The SFC model as a graphical producer (the PLCopen importer) fills it: a chart built in C++,
// lowered into a parsed POU through a compiler front-end, compiled and run on the soft PLC.
#include <gtest/gtest.h>

#include "core/clock.hpp"
#include "lang/sfc/lower.hpp"
#include "lang/sfc/step_monitor.hpp"
#include "lang/st/compiler.hpp"
#include "lang/st/parse/parser.hpp"
#include "plc/runtime.hpp"

namespace virtcom::sfc {
namespace {

// MAIN with its variables; DONOR only lends parsed statements and expressions to the chart.
constexpr std::string_view kSource = R"ST(
PROGRAM MAIN
VAR go : BOOL := TRUE; n : INT; lamp : BOOL; END_VAR
END_PROGRAM
PROGRAM DONOR
VAR go : BOOL; n : INT; Leave : BOOL; END_VAR
n := n + 1;
Leave := n >= 3;
go := go;
END_PROGRAM
)ST";

NamedRef ref(std::string name) { return {std::move(name), {}}; }

// Init -(go)-> Work -(Leave: an ST body, n >= 3)-> Init; Work runs the chart's own action Inc
// (N) and drives the BOOL variable lamp (N).
void buildChart(st::CompilationUnit& unit, Diagnostics& diags, st::NodeId& nextNodeId, bool clashingAction) {
  st::Pou& main = *unit.pous[0];
  st::Pou& donor = *unit.pous[1];
  Chart chart;
  chart.steps.push_back({"Init", {}, true, {}});
  Step work{"Work", {}, false, {}};
  work.actions.push_back({ref("Inc"), Qualifier::N, nullptr, {}, {}});
  work.actions.push_back({ref("lamp"), Qualifier::N, nullptr, {}, {}});
  chart.steps.push_back(std::move(work));
  Transition start;
  start.from = {ref("Init")};
  start.to = {ref("Work")};
  start.condition = std::move(donor.body[2]->rhs);
  chart.transitions.push_back(std::move(start));
  Transition leave;
  leave.name = "Leave";
  leave.from = {ref("Work")};
  leave.to = {ref("Init")};
  leave.body.push_back(std::move(donor.body[1]));
  chart.transitions.push_back(std::move(leave));
  Action inc{clashingAction ? "Extra" : "Inc", {}, {}};
  inc.body.push_back(std::move(donor.body[0]));
  chart.actions.push_back(std::move(inc));
  if (clashingAction) chart.actions.push_back({"extra", {}, {}});
  donor.body.clear();
  lowerChart(std::move(chart), main, diags, nextNodeId);
}

std::unique_ptr<bc::Module> compile(bool clashingAction, Diagnostics& diags) {
  SourceManager sources;
  st::SourceInput input{"chart.st", std::string(kSource)};
  input.frontEnd = [clashingAction](uint32_t fileId, std::string_view text, Diagnostics& d, st::NodeId& nextNodeId) {
    st::CompilationUnit unit = st::parseFile(fileId, text, d, nextNodeId);
    buildChart(unit, d, nextNodeId, clashingAction);
    return unit;
  };
  return st::compileProgram({input}, sources, diags);
}

TEST(ChartModel, ProducerBuiltChartRunsWithItsOwnActions) {
  Diagnostics diags;
  auto module = compile(false, diags);
  ASSERT_NE(module, nullptr) << diags.all().front().message;
  VirtualClock clock;
  plc::Runtime runtime(*module, clock, {});
  ASSERT_TRUE(runtime.coldStart());
  std::vector<StepVariable> steps = findSteps(*module);
  ASSERT_EQ(steps.size(), 2u);
  std::vector<std::string> seen;
  std::string active;
  for (int scan = 0; scan < 6; ++scan) {
    ASSERT_TRUE(runtime.tick()) << runtime.faultText();
    formatActiveSteps(steps, runtime.machine().memory(), active);
    seen.push_back(active);
  }
  // Work is entered in scan 2; Inc counts 1, 2, 3 in scans 2-4; Leave sees n >= 3 in scan 5,
  // when Inc runs its final scan (4); Init is left again in scan 6 (go stays TRUE).
  EXPECT_EQ(seen, (std::vector<std::string>{"MAIN.Init", "MAIN.Work", "MAIN.Work", "MAIN.Work", "MAIN.Init", "MAIN.Work"}));
  auto n = bc::resolveVariable(*module, "MAIN.n");
  auto lamp = bc::resolveVariable(*module, "MAIN.lamp");
  ASSERT_TRUE(n && lamp);
  EXPECT_EQ(bc::formatValue(*module, *n, runtime.machine().memory()), "5");
  EXPECT_EQ(bc::formatValue(*module, *lamp, runtime.machine().memory()), "TRUE");
}

TEST(ChartModel, DuplicateChartActionsAreReported) {
  Diagnostics diags;
  EXPECT_EQ(compile(true, diags), nullptr);
  ASSERT_FALSE(diags.all().empty());
  EXPECT_EQ(diags.all().front().code, "E403");
  EXPECT_NE(diags.all().front().message.find("action 'extra' is already declared"), std::string::npos)
      << diags.all().front().message;
}

TEST(ChartModel, QualifierSpellingsRoundTrip) {
  for (std::string_view text : {"N", "R", "S", "L", "D", "P", "P0", "P1", "SD", "DS", "SL"}) {
    std::optional<Qualifier> q = qualifierFromText(text);
    ASSERT_TRUE(q) << text;
    EXPECT_EQ(qualifierSpelling(*q), text);
  }
  EXPECT_EQ(qualifierFromText("sd"), Qualifier::SD);
  EXPECT_FALSE(qualifierFromText("X"));
  EXPECT_TRUE(qualifierNeedsTime(Qualifier::SL));
  EXPECT_FALSE(qualifierNeedsTime(Qualifier::P0));
}

}  // namespace
}  // namespace virtcom::sfc

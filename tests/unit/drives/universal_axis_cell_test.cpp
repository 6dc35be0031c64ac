// The point of the universal axis (docs/universal-axis.md): one UNIVERSAL_AXIS instance and one PLC
// program drive a Siemens G120 (telegram 1) and a Rockwell PowerFlex 525 (EtherNet/IP) through
// the cell's `mapping:` only; both reach 675 rpm forward and -675 rpm backward.
#include <gtest/gtest.h>

#include <filesystem>

#include "bytecode/module.hpp"
#include "cell/cell.hpp"
#include "sim/simulation.hpp"

namespace fs = std::filesystem;
using namespace virtcom;

namespace {

const fs::path kDir = fs::path(VIRTCOM_SOURCE_DIR) / "tests" / "unit" / "drives" / "universal_axis";

std::string value(cell::Cell& c, sim::Simulation& s, const std::string& name) {
  auto ref = bc::resolveVariable(*c.module, name);
  if (!ref) return "unknown " + name;
  return bc::formatValue(*c.module, *ref, s.plc().machine().memory());
}

double number(cell::Cell& c, sim::Simulation& s, const std::string& name) { return std::stod(value(c, s, name)); }

struct CellRun {
  SourceManager sources;
  Diagnostics diags;
  std::unique_ptr<cell::Cell> cell;
  std::unique_ptr<sim::Simulation> sim;
};

void load(CellRun& r, const fs::path& file) {
  r.cell = cell::loadCell(file.string(), r.sources, r.diags);
  ASSERT_NE(r.cell, nullptr) << r.diags.render(r.sources);
  r.sim = std::make_unique<sim::Simulation>(*r.cell, sim::SimOptions{});
  r.sim->run();
}

void run(CellRun& r, const std::string& file) {
  load(r, kDir / file);
  if (r.cell) {
    ASSERT_EQ(value(*r.cell, *r.sim, "MAIN.phase"), "3") << "the run did not finish its sequence";
  }
}

TEST(UniversalAxisCell, SameBlockDrivesSiemensAndRockwell) {
  for (const char* file : {"g120.yaml", "pf525.yaml"}) {
    SCOPED_TRACE(file);
    CellRun r;
    run(r, file);
    if (!r.cell) continue;
    EXPECT_NEAR(number(*r.cell, *r.sim, "MAIN.forwardRpm"), 675.0, 2.0);
    EXPECT_NEAR(number(*r.cell, *r.sim, "MAIN.backwardRpm"), -675.0, 2.0);
    EXPECT_EQ(value(*r.cell, *r.sim, "MAIN.forwardDir"), "TRUE");
    EXPECT_EQ(value(*r.cell, *r.sim, "MAIN.backwardDir"), "TRUE");
    EXPECT_EQ(value(*r.cell, *r.sim, "MAIN.axis.OUT_Status"), "28674") << "16#7002";
  }
}

// Siemens side in raw words: the G120 received 50 % = NSOLL_A 8192 (675 rpm) with the mapping.
TEST(UniversalAxisCell, MappedPortsAreTheBlockSignals) {
  CellRun r;
  run(r, "g120.yaml");
  if (!r.cell) return;
  const auto& ports = r.cell->devices[0]->ports();
  auto has = [&](const char* name) {
    for (const auto& p : ports)
      if (p.name == name) return true;
    return false;
  };
  EXPECT_TRUE(has("Control_Start"));
  EXPECT_TRUE(has("Status_ActualSpeed"));
  EXPECT_TRUE(has("Cfg_RefSpeed"));
  EXPECT_FALSE(has("STW1")) << "a mapped drive exposes block signals, not telegram words";
  EXPECT_EQ(value(*r.cell, *r.sim, "MAIN.axis.Cfg_RefSpeed"), "1350.0") << "set by the mapping";
}

TEST(UniversalAxisCell, MappingForAnotherTelegramIsRejected) {
  SourceManager sources;
  Diagnostics diags;
  auto c = cell::loadCell((kDir / "wrong_telegram.yaml").string(), sources, diags);
  EXPECT_EQ(c, nullptr);
  EXPECT_NE(diags.render(sources).find("wrong_telegram.yaml:8:5: error[C010]: the mapping is for telegram ab_pf525_velocity "
                                       "but this drive speaks siemens_std1"),
            std::string::npos)
      << diags.render(sources);
}

// A mapping whose reference speed is not the drive's p2000 loads, with a warning at the mapping's
// value (issue 16: 1350 vs 1500 rpm made the PLC read every speed 10 % off without a word). The
// matching bundled cell has no warning.
TEST(UniversalAxisCell, ReferenceSpeedOtherThanP2000Warns) {
  SourceManager sources;
  Diagnostics diags;
  auto c = cell::loadCell((kDir / "p2000_mismatch.yaml").string(), sources, diags);
  ASSERT_NE(c, nullptr) << diags.render(sources);
  ASSERT_EQ(diags.warningCount(), 1u) << diags.render(sources);
  EXPECT_NE(diags.render(sources).find("telegram1.yaml:6:30: warning[C012]: the mapping's Cfg_RefSpeed is 1350 rpm but the "
                                       "drive's p2000 is 1500 rpm: the PLC reads every speed scaled by 1500/1350 (set both to "
                                       "the drive's reference speed)"),
            std::string::npos)
      << diags.render(sources);
  CellRun matching;
  run(matching, "g120.yaml");
  EXPECT_EQ(matching.diags.warningCount(), 0u) << matching.diags.render(matching.sources);
}

// examples/drives/epos: reference point, absolute moves to 70000 and 10000 LU, a jog, all
// through UNIVERSAL_AXIS and the telegram 111 mapping.
TEST(UniversalAxisCell, EposExampleRunsItsSequence) {
  CellRun r;
  load(r, fs::path(VIRTCOM_SOURCE_DIR) / "examples" / "drives" / "epos" / "cell.yaml");
  if (!r.cell) return;
  EXPECT_EQ(value(*r.cell, *r.sim, "MAIN.done"), "TRUE");
  EXPECT_NEAR(number(*r.cell, *r.sim, "MAIN.reachedFirst"), 70000, 40);
  EXPECT_NEAR(number(*r.cell, *r.sim, "MAIN.reachedSecond"), 10000, 40);
  EXPECT_GT(number(*r.cell, *r.sim, "MAIN.jogEnd"), 10000 + 1000) << "jog + moved forward";
  EXPECT_EQ(value(*r.cell, *r.sim, "MAIN.axis.OUT_Reference_Setted"), "TRUE");
  EXPECT_EQ(value(*r.cell, *r.sim, "MAIN.axis.OUT_Blocked"), "FALSE");
}

}  // namespace

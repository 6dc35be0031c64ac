// Transition conditions in every TC6 form (sfc_conditions.xml: inline ST, LD and FBD, a reference,
// conditions wired from LD contacts, an FBD function, an FB instance and an edge contact of the
// SFC body, a negated condition) and macro steps expanded in place (sfc_macro_step.xml).
#include "plcopen_fixture.hpp"

namespace virtcom::plcopen::testing {
namespace {

class Chart : public ::testing::Test {
 protected:
  void load(const std::string& file, std::string program, std::vector<std::string> steps) {
    compiled_ = compileGolden(file);
    ASSERT_NE(compiled_->module, nullptr) << compiled_->rendered();
    plc_ = std::make_unique<Plc>(*compiled_->module);
    program_ = std::move(program);
    steps_ = std::move(steps);
  }
  std::string active() {
    std::string out;
    for (const std::string& step : steps_)
      if (plc_->get(program_ + "." + step + ".X") == "TRUE") out += (out.empty() ? "" : ",") + step;
    return out;
  }
  void set(const std::string& variable, const std::string& value) { plc_->set(program_ + "." + variable, value); }
  // Sets `variable`, scans, clears it again: the transition it clears fires in that one scan.
  void pulse(const std::string& variable) {
    set(variable, "TRUE");
    plc_->scan();
    set(variable, "FALSE");
  }
  // With `variable` at `holding` the chart stays in `from`; at `firing` it moves on to `to`.
  void expectFiresOn(const std::string& variable, const std::string& holding, const std::string& firing,
                     const std::string& from, const std::string& to) {
    set(variable, holding);
    plc_->scan();
    EXPECT_EQ(active(), from) << variable << " = " << holding;
    set(variable, firing);
    plc_->scan();
    EXPECT_EQ(active(), to) << variable << " = " << firing;
  }
  std::unique_ptr<Compiled> compiled_;
  std::unique_ptr<Plc> plc_;
  std::string program_;
  std::vector<std::string> steps_;
};

class Conditions : public Chart {
 protected:
  void SetUp() override { load("sfc_conditions.xml", "seq", {"S0", "S1", "S2", "S3", "S4", "S5", "S6", "S7", "S8"}); }
};

TEST_F(Conditions, EachFormHoldsUntilItsConditionBecomesTrue) {
  plc_->scan();
  EXPECT_EQ(active(), "S0");
  pulse("start");
  EXPECT_EQ(active(), "S1") << "inline ST";
  plc_->scan();
  EXPECT_EQ(active(), "S1");
  pulse("a");
  EXPECT_EQ(active(), "S2") << "inline LD: the coil assigns the inline's name";
  expectFiresOn("level", "2", "3", "S2", "S3");  // inline FBD: level >= 3
  pulse("ready");
  EXPECT_EQ(active(), "S4") << "reference to an FBD transition";
}

TEST_F(Conditions, WiredFromContactsAndAFunction) {
  plc_->scan();
  for (const char* v : {"start", "a", "ready"}) set(v, "TRUE");
  set("level", "3");
  plc_->scan(4);
  ASSERT_EQ(active(), "S4");
  set("b", "TRUE");
  expectFiresOn("c", "TRUE", "FALSE", "S4", "S5");  // b AND NOT c: the negated contact c blocks
  expectFiresOn("pressure", "5", "6", "S5", "S6");  // GT(pressure, 5)
}

TEST_F(Conditions, WiredFromAnFbInstanceAnEdgeAndNegated) {
  plc_->scan();
  for (const char* v : {"start", "a", "ready", "b", "hold"}) set(v, "TRUE");
  set("level", "3");
  set("pressure", "6");
  plc_->scan(6);
  ASSERT_EQ(active(), "S6");
  EXPECT_EQ(plc_->get("seq.delay.Q"), "FALSE") << "the TON is called while S6 is active";
  int scans = 0;
  while (active() == "S6" && scans < 10) {
    plc_->scan();
    ++scans;
  }
  EXPECT_EQ(active(), "S7") << "delay.Q (T#30ms) clears the transition";
  EXPECT_GT(scans, 1) << "not before the timer ran out";
  plc_->scan(2);
  EXPECT_EQ(active(), "S7");
  set("pulse", "TRUE");
  plc_->scan();
  EXPECT_EQ(active(), "S8") << "the rising edge of pulse";
  plc_->scan();
  EXPECT_EQ(active(), "S8") << "negated: hold is TRUE";
  set("hold", "FALSE");
  plc_->scan();
  EXPECT_EQ(active(), "S0") << "negated: NOT hold, then the jump to S0";
}

// Two transitions wired from one rising-edge contact (sfc_shared_condition.xml): each keeps its
// own hidden variables (edge memory, transition name), so the POU declares no name twice.
TEST(WiredConditions, TwoTransitionsMayReadOneElement) {
  auto c = compileGolden("sfc_shared_condition.xml");
  ASSERT_NE(c->module, nullptr) << c->rendered();
  Plc plc(*c->module);
  plc.scan(2);
  EXPECT_EQ(plc.get("P.S0.X"), "TRUE");
  plc.set("P.e", "TRUE");
  plc.scan();
  EXPECT_EQ(plc.get("P.S1.X"), "TRUE") << "the edge clears both; priority 0 fires";
  EXPECT_EQ(plc.get("P.S2.X"), "FALSE");
}

class MacroStep : public Chart {
 protected:
  void SetUp() override {
    load("sfc_macro_step.xml", "tank", {"Idle", "Fill__Open", "Fill__Dose__Pump", "Fill__Dose__Wait", "Fill__Close", "Done"});
  }
};

TEST_F(MacroStep, IsEnteredThroughItsInitialStepAndLeftThroughItsFinalStep) {
  plc_->scan();
  EXPECT_EQ(active(), "Idle");
  pulse("go");
  EXPECT_EQ(active(), "Fill__Open");
  EXPECT_EQ(plc_->get("tank.valve"), "TRUE") << "the macro's own action blocks run";
  pulse("closed");
  EXPECT_EQ(active(), "Fill__Open") << "the transition after the macro step waits for its final step";
  pulse("full");
  EXPECT_EQ(active(), "Fill__Dose__Pump") << "a nested macro step";
  EXPECT_EQ(plc_->get("tank.pumping"), "TRUE");
  pulse("dosed");
  EXPECT_EQ(active(), "Fill__Dose__Wait");
  pulse("settled");
  EXPECT_EQ(active(), "Fill__Close");
  pulse("closed");
  EXPECT_EQ(active(), "Done");
  pulse("again");
  EXPECT_EQ(active(), "Fill__Open") << "a jump to the macro step enters its initial step";
}

}  // namespace
}  // namespace virtcom::plcopen::testing

// Scenario files: their mistakes as diagnostics at file:line:col, parameter rows, finding and
// filtering cases, and the JUnit XML of a run.
#include <gtest/gtest.h>

#include "scenario/junit.hpp"
#include "scenario/scenario_file.hpp"
#include "scenario/suite.hpp"
#include "scenario_fixture.hpp"

namespace virtcom::scenario::test {
namespace {

struct ErrorCase {
  const char* name;
  const char* body;
  const char* diagnostic;
};

const ErrorCase kErrors[] = {
    {"UnknownVariableInCondition", "expect:\n  - {final: \"MAIN.stat = 3\"}\n",
     "test.yaml:3:13: error[C061]: condition 'MAIN.stat = 3': 'MAIN.stat' is neither a device signal (e.g. Robot1.busy), a world fact (world.NAME) nor a variable of the PLC"},
    {"MissingOperand", "expect:\n  - {final: \"MAIN.state = 3 AND\"}\n",
     "test.yaml:3:31: error[C061]: condition 'MAIN.state = 3 AND': a value or a name is missing at the end"},
    {"UnknownFact", "expect:\n  - {final: world.nothing}\n",
     "test.yaml:3:13: error[C061]: condition 'world.nothing': the cell has no world fact 'nothing'"},
    {"UnknownKey", "expect:\n  - {final: MAIN.failed, whithin: 2 s}\n", "test.yaml:3:26: error[C011]: unknown key 'whithin' in assertion"},
    {"UnknownAssertion", "expect:\n  - {sometimes: MAIN.failed}\n", "test.yaml:3:5: error[C010]: an assertion is one of: at + that"},
    {"StepWithoutTime", "steps:\n  - {set: {MAIN.start: TRUE}}\n", "test.yaml:3:5: error[C010]: a step has either 'at: TIME' or 'when: CONDITION'"},
    {"UnknownDevice", "faults:\n  - {device: Clamb, error_code: 90}\n", "test.yaml:3:14: error[C010]: no device named 'Clamb' (the cell has: Clamp, PartSensor)"},
    {"StuckOutputNotABit", "faults:\n  - {device: PartSensor, stuck_output: 2}\n", "test.yaml:3:5: error[C010]: 'stuck_output' must be 0 or 1 (or -1: not stuck)"},
    {"BadValue", "set: {MAIN.start: 7}\n", "test.yaml:2:19: error[C060]: 'MAIN.start': "},
    {"UnknownVariableInSet", "set: {MAIN.begin: TRUE}\n", "test.yaml:2:7: error[C060]: the PLC has no variable 'MAIN.begin'"},
    {"TimeWithoutUnit", "steps:\n  - {at: 2, set: {MAIN.start: TRUE}}\n", "test.yaml:3:10: error[C010]: 'at': '2' needs a unit"},
    {"UnknownParameter", "expect:\n  - {final: \"MAIN.state = ${s}\"}\nparameters:\n  - {t: 1}\n",
     "test.yaml:3:13: error[C060]: '${s}' names no parameter (the row has: t)"},
};

class ScenarioErrors : public ScenarioTest, public ::testing::WithParamInterface<ErrorCase> {};

TEST_P(ScenarioErrors, ReportedAtTheirPosition) {
  const ErrorCase& c = GetParam();
  const bool rows = std::string(c.body).find("parameters") != std::string::npos;
  CaseResult r = run(c.body, rows ? 0 : SIZE_MAX);
  ASSERT_EQ(r.verdict, Verdict::Error);
  EXPECT_TRUE(firstDiagnostic(r).starts_with(c.diagnostic)) << firstDiagnostic(r);
}

INSTANTIATE_TEST_SUITE_P(Scenario, ScenarioErrors, ::testing::ValuesIn(kErrors),
                         [](const ::testing::TestParamInfo<ErrorCase>& info) { return std::string(info.param.name); });

TEST_F(ScenarioTest, ParameterRowsBecomeCasesWithTheirValues) {
  const std::string path = write(R"(name: clamp
set: {MAIN.start: TRUE}
parameters:
  - {t: 0.5 s, s: 1}
  - {t: 1.5 s, s: 2}
expect:
  - {at: "${t}", that: "MAIN.state = ${s}"}
)");
  std::string error;
  std::vector<CaseSpec> cases = collectCases({dir_.string()}, "", error);
  ASSERT_EQ(cases.size(), 2u) << error;
  EXPECT_EQ(cases[0].name, "clamp[t=0.5 s,s=1]");
  EXPECT_EQ(cases[1].name, "clamp[t=1.5 s,s=2]");
  EXPECT_EQ(runCase(cases[0], {}).verdict, Verdict::Pass);
  CaseResult second = runCase(cases[1], {});
  EXPECT_EQ(second.verdict, Verdict::Fail);  // the run ends at 1.03 s
  EXPECT_NE(text(second).find("before 1.5 s"), std::string::npos) << text(second);
  EXPECT_EQ(collectCases({path}, "*s=2*", error).size(), 1u);
}

TEST(ScenarioSuite, GlobMatchesStarsAndQuestionMarks) {
  EXPECT_TRUE(globMatches("cycle*", "cycle_time[sequence=1]"));
  EXPECT_TRUE(globMatches("*[sequence=?]", "cycle_time[sequence=3]"));
  EXPECT_TRUE(globMatches("*", ""));
  EXPECT_FALSE(globMatches("cycle", "cycle_time"));
  EXPECT_FALSE(globMatches("*press?", "press"));
}

TEST(ScenarioSuite, MissingPathIsAnError) {
  std::string error;
  EXPECT_TRUE(collectCases({"/nonexistent/scenarios"}, "", error).empty());
  EXPECT_EQ(error, "'/nonexistent/scenarios' is neither a scenario file nor a directory");
}

TEST(ScenarioJunit, CountsAndElementsPerVerdict) {
  std::vector<CaseResult> results(4);
  const Verdict verdicts[] = {Verdict::Pass, Verdict::Fail, Verdict::Error, Verdict::ExpectedFail};
  for (size_t i = 0; i < results.size(); ++i) {
    results[i].spec = {i < 2 ? "a.yaml" : "b.yaml", SIZE_MAX, "case<" + std::to_string(i) + ">", i < 2 ? "tests.a" : "tests.b"};
    results[i].verdict = verdicts[i];
    results[i].runEnd = "completed: done";
    if (i) results[i].messages.push_back("a.yaml:3: final x: at 1 s: 'x & y' is false");
  }
  const std::string xml = junitXml(results);
  EXPECT_NE(xml.find("<testsuites name=\"virtcom test\" tests=\"4\" failures=\"1\" errors=\"1\" skipped=\"1\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("<testsuite name=\"tests.a\" tests=\"2\" failures=\"1\" errors=\"0\" skipped=\"0\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("<testcase name=\"case&lt;0&gt;\" classname=\"tests.a\" time=\"0.000\"/>"), std::string::npos) << xml;
  EXPECT_NE(xml.find("<failure message=\"a.yaml:3: final x: at 1 s: &apos;x &amp; y&apos; is false\" type=\"assertion\">"), std::string::npos) << xml;
  EXPECT_NE(xml.find("<error message="), std::string::npos);
  EXPECT_NE(xml.find("<skipped message=\"xfail: "), std::string::npos);
}

}  // namespace
}  // namespace virtcom::scenario::test

// End-to-end tests of `virtcom test` (docs/scenarios.md): the built binary runs the gearbox
// cell's commissioning test plan (examples/gearbox-cell/tests), the drives' fault handling
// (examples/drives/tests) and the scenarios of
// tests/e2e/data/scenarios/suite (one passing, a table with a failing row, one that cannot run),
// and is checked on its exit status, its lines, the JUnit XML (validated by xmllint against
// tests/e2e/data/scenarios/junit.xsd), the reports of failing cases, and on giving the same
// results with --jobs 1 and --jobs 2.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>

#include "shell_command.hpp"
#include "support/read_file.hpp"

namespace fs = std::filesystem;

namespace {

using virtcom::e2e::shell;
using virtcom::test::readFile;

const std::string kExe = VIRTCOM_EXE;
const std::string kSource = VIRTCOM_SOURCE_DIR;
const std::string kSuite = "tests/e2e/data/scenarios/suite";
const std::string kXsd = kSource + "/tests/e2e/data/scenarios/junit.xsd";

class TestCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("virtcom-test-e2e-" + std::to_string(getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  // Runs `virtcom test ARGS` in the source tree (short relative paths in the output).
  int test(const std::string& args, std::string& out) { return shell("cd " + kSource + " && " + kExe + " test " + args, out); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  void expectValidJunit(const std::string& file) {
    std::string out;
    EXPECT_EQ(shell("xmllint --noout --schema " + kXsd + " " + file, out), 0) << out << readFile(file);
  }
  fs::path dir_;
};

TEST_F(TestCommand, GearboxCommissioningPlanPasses) {
  std::string out;
  ASSERT_EQ(test("examples/gearbox-cell/tests --jobs 2 --junit " + path("plan.xml"), out), 0) << out;
  EXPECT_NE(out.find("PASS  cycle time[sequence=1,min=99.75 s,max=100.75 s,robot2=15.5 kJ]"), std::string::npos) << out;
  EXPECT_NE(out.find("PASS  cycle time[sequence=3,"), std::string::npos) << out;
  EXPECT_NE(out.find("PASS  press error mid-cycle"), std::string::npos) << out;
  EXPECT_NE(out.find("PASS  screwer without a stud"), std::string::npos) << out;
  EXPECT_NE(out.find("PASS  Robot2 done never arrives"), std::string::npos) << out;
  EXPECT_NE(out.find("XFAIL  sequence 4 collides"), std::string::npos) << out;
  EXPECT_NE(out.find("collided in SharedTable"), std::string::npos) << out;
  EXPECT_NE(out.find("PASS  emergency stop and restart"), std::string::npos) << out;
  EXPECT_NE(out.find("8 scenario(s): 7 passed, 0 failed, 1 failed as expected (xfail)"), std::string::npos) << out;
  expectValidJunit(path("plan.xml"));
}

TEST_F(TestCommand, DrivesFaultHandlingPlanPasses) {
  std::string out;
  ASSERT_EQ(test("examples/drives/tests --jobs 2", out), 0) << out;
  for (const char* drive : {"g120", "g120_352", "pf525", "pf750"})
    EXPECT_NE(out.find(std::string("PASS  fault recovered[drive=") + drive + "]"), std::string::npos) << drive << "\n" << out;
  EXPECT_NE(out.find("PASS  comm loss in the backward phase"), std::string::npos) << out;
  EXPECT_NE(out.find("6 scenario(s): 6 passed, 0 failed"), std::string::npos) << out;
}

TEST_F(TestCommand, FailuresGiveTheAssertionTimeAndValuesReportsAndExitStatus) {
  std::string out;
  ASSERT_EQ(test(kSuite + " --jobs 2 --junit " + path("suite.xml") + " --report-dir " + path("reports"), out), 5) << out;
  EXPECT_NE(out.find("ERROR  broken scenario"), std::string::npos) << out;
  EXPECT_NE(out.find("broken.yaml:5:32: error[C061]: condition 'MAIN.parts = 1 AND MAIN.stat = 3'"), std::string::npos) << out;
  EXPECT_NE(out.find("PASS  clamp passes"), std::string::npos) << out;
  EXPECT_NE(out.find("PASS  clamp too slow[at=0.5 s,state=1]"), std::string::npos) << out;
  EXPECT_NE(out.find("FAIL  clamp too slow[at=0.8 s,state=2]"), std::string::npos) << out;
  EXPECT_NE(out.find("clamp_too_slow.yaml:10: at 0.8 s that MAIN.state = 2: at 0.8 s: 'MAIN.state = 2' is false (MAIN.state = 1)"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("4 scenario(s): 2 passed, 2 failed"), std::string::npos) << out;
  expectValidJunit(path("suite.xml"));
  const std::string xml = readFile(path("suite.xml"));
  EXPECT_NE(xml.find("tests=\"4\" failures=\"1\" errors=\"1\" skipped=\"0\""), std::string::npos) << xml;
  // The failing cases' reports, the passing ones' not.
  EXPECT_TRUE(fs::exists(path("reports/clamp_too_slow_at_0.8_s_state_2_.html")));
  const std::string vcd = readFile(path("reports/clamp_too_slow_at_0.8_s_state_2_.vcd"));
  EXPECT_NE(vcd.find("$scope module Clamp $end"), std::string::npos) << vcd;
  EXPECT_NE(vcd.find(" busy $end"), std::string::npos) << vcd;
  EXPECT_FALSE(fs::exists(path("reports/clamp_passes.html")));
}

TEST_F(TestCommand, ResultsDoNotDependOnJobs) {
  std::string one, two;
  test(kSuite + " examples/gearbox-cell/tests --jobs 1 --junit " + path("one.xml") + " --report-dir " + path("one"), one);
  test(kSuite + " examples/gearbox-cell/tests --jobs 2 --junit " + path("two.xml") + " --report-dir " + path("two"), two);
  EXPECT_EQ(one, two);
  const std::regex time(" time=\"[0-9.]+\"");
  EXPECT_EQ(std::regex_replace(readFile(path("one.xml")), time, ""), std::regex_replace(readFile(path("two.xml")), time, ""));
  size_t reports = 0;
  for (const auto& entry : fs::directory_iterator(path("one"))) {
    EXPECT_EQ(readFile(entry.path().string()), readFile(path("two/" + entry.path().filename().string()))) << entry.path();
    ++reports;
  }
  EXPECT_EQ(reports, 2u);  // the failing row's HTML and VCD
}

// --backend: the verdicts, messages and failing cases' reports are the same on the interpreter,
// on machine code compiled before the run and on the tiered backend (auto).
TEST_F(TestCommand, ResultsDoNotDependOnTheBackend) {
  const std::string cases = kSuite + " examples/gearbox-cell/tests/press_error.yaml examples/gearbox-cell/tests/emergency_stop.yaml --jobs 2";
  const std::regex time(" time=\"[0-9.]+\"");
  std::string interp;
  EXPECT_EQ(test(cases + " --backend interp --junit " + path("interp.xml") + " --report-dir " + path("interp"), interp), 5) << interp;
  EXPECT_NE(interp.find("6 scenario(s): 4 passed, 2 failed"), std::string::npos) << interp;
  for (const std::string backend : {"aot", "auto"}) {
    std::string out;
    test(cases + " --backend " + backend + " --junit " + path(backend + ".xml") + " --report-dir " + path(backend), out);
    EXPECT_EQ(out, interp) << backend;
    EXPECT_EQ(std::regex_replace(readFile(path(backend + ".xml")), time, ""), std::regex_replace(readFile(path("interp.xml")), time, ""));
    for (const auto& entry : fs::directory_iterator(path("interp")))
      EXPECT_EQ(readFile(entry.path().string()), readFile(path(backend + "/" + entry.path().filename().string()))) << entry.path();
  }
}

TEST_F(TestCommand, FilterSelectsCasesByName) {
  std::string out;
  ASSERT_EQ(test(kSuite + " --filter 'clamp too*state=1]'", out), 0) << out;
  EXPECT_NE(out.find("1 scenario(s): 1 passed, 0 failed"), std::string::npos) << out;
  out.clear();
  EXPECT_EQ(test(kSuite + " --filter 'nothing*'", out), 64) << out;
  EXPECT_NE(out.find("error: no scenario found matching --filter 'nothing*'"), std::string::npos) << out;
  out.clear();
  EXPECT_EQ(test("no/such/dir", out), 64) << out;
  EXPECT_NE(out.find("'no/such/dir' is neither a scenario file nor a directory"), std::string::npos) << out;
}

// The lines of an lcov tracefile that ran at least once ("DA:LINE,COUNT" with COUNT > 0).
size_t linesHit(const std::string& info) {
  const std::regex hit("\nDA:[0-9]+,[1-9]");
  return static_cast<size_t>(std::distance(std::sregex_iterator(info.begin(), info.end(), hit), std::sregex_iterator()));
}

// --coverage: every case's counts added up, the same file whatever --jobs; the whole plan
// reaches lines that one of its cases alone does not; Debian's lcov reads the file.
TEST_F(TestCommand, CoverageAddsUpEveryCaseWhateverTheJobs) {
  std::string out;
  ASSERT_EQ(test("examples/gearbox-cell/tests --jobs 1 --coverage " + path("one.info"), out), 0) << out;
  EXPECT_NE(out.find("MAIN"), std::string::npos) << "the per-POU summary\n" << out;
  ASSERT_EQ(test("examples/gearbox-cell/tests --jobs 2 --coverage " + path("two.info") + " --coverage-xml " + path("two.xml"), out), 0)
      << out;
  const std::string all = readFile(path("one.info"));
  EXPECT_EQ(all, readFile(path("two.info")));
  EXPECT_NE(readFile(path("two.xml")).find("<coverage"), std::string::npos);
  ASSERT_EQ(test("examples/gearbox-cell/tests --filter 'screwer*' --coverage " + path("screwer.info"), out), 0) << out;
  EXPECT_GT(linesHit(all), linesHit(readFile(path("screwer.info"))));
  EXPECT_GT(linesHit(readFile(path("screwer.info"))), 10u);
  ASSERT_EQ(shell("lcov --summary " + path("one.info"), out), 0) << out;
  EXPECT_NE(out.find("lines"), std::string::npos) << out;
}

// Scenarios of a PLC program alone (`program:`, tests/e2e/data/scenarios/program): the passing and
// the failing case as with a cell, the failure's time and values, JUnit, and the program's
// coverage (its 6 statements and 3 branch arms all reached by the two cases together).
TEST_F(TestCommand, ProgramAloneScenariosRunWithJunitAndCoverage) {
  std::string out;
  ASSERT_EQ(test("tests/e2e/data/scenarios/program --junit " + path("program.xml") + " --coverage " + path("program.info"), out), 5)
      << out;
  EXPECT_NE(out.find("PASS  latch holds and runs on  (tests/e2e/data/scenarios/program/latch_passes.yaml, time limit reached at 3 s)"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("latch_both_pressed.yaml:9: at 0.25 s that MAIN.running: at 0.25 s: 'MAIN.running' is false (MAIN.running = FALSE)"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("2 scenario(s): 1 passed, 1 failed"), std::string::npos) << out;
  expectValidJunit(path("program.xml"));
  const std::string info = readFile(path("program.info"));
  EXPECT_NE(info.find("SF:tests/e2e/data/scenarios/program/latch.st"), std::string::npos) << info;
  EXPECT_EQ(linesHit(info), 6u) << info;
  EXPECT_NE(out.find("MAIN      6/6 100.0%        3/3 100.0%"), std::string::npos) << out;
}

// Compares with the golden file; VIRTCOM_UPDATE_GOLDEN=1 rewrites it for review in the diff.
void expectGolden(const std::string& actual, const std::string& file) {
  if (std::getenv("VIRTCOM_UPDATE_GOLDEN")) std::ofstream(file, std::ios::binary) << actual;
  EXPECT_EQ(actual, readFile(file)) << "differs from " << file << " (VIRTCOM_UPDATE_GOLDEN=1 rewrites it)";
}

// Activity-diagram rules in the coverage files (docs/coverage.md): the two scenarios of
// tests/e2e/data/scenarios/signal_plan exercise 3 of the 4 rules of signals.ad, whose comments
// count every firing; the tracefile and the Cobertura XML are the golden files beside it,
// whatever --jobs; Debian's lcov and genhtml read them.
TEST_F(TestCommand, CoverageCountsActivityDiagramRules) {
  const std::string plan = "tests/e2e/data/scenarios/signal_plan";
  const std::string golden = kSource + "/tests/e2e/data/scenarios/signals/coverage";
  std::string out;
  ASSERT_EQ(test(plan + " --jobs 2 --coverage " + path("two.info") + " --coverage-xml " + path("two.xml"), out), 0) << out;
  EXPECT_NE(out.find("2 scenario(s): 2 passed"), std::string::npos) << out;
  EXPECT_TRUE(std::regex_search(out, std::regex("transitions +rules\n"))) << out;
  EXPECT_TRUE(std::regex_search(out, std::regex("\nSignals.Lights +2/2 100.0% +- +- +- +2/2 100.0%\n"))) << out;
  EXPECT_TRUE(std::regex_search(out, std::regex("\nSignals.Alarm +0/1 0.0% +- +- +- +0/1 0.0%\n"))) << out;
  EXPECT_TRUE(std::regex_search(out, std::regex("\ntotal +[0-9/. %]+- +- +- +3/4 75.0%\n"))) << out;
  const std::string info = readFile(path("two.info"));
  expectGolden(info, golden + ".info");
  expectGolden(readFile(path("two.xml")), golden + ".xml");
  ASSERT_EQ(test(plan + " --jobs 1 --coverage " + path("one.info"), out), 0) << out;
  EXPECT_EQ(readFile(path("one.info")), info);
  // go.yaml alone never halts: the Stopping rule is not hit.
  ASSERT_EQ(test(plan + " --filter go --coverage " + path("go.info"), out), 0) << out;
  EXPECT_TRUE(std::regex_search(out, std::regex("\ntotal +[0-9/. %]+- +- +- +2/4 50.0%\n"))) << out;
  EXPECT_NE(readFile(path("go.info")).find("\nDA:42,0\n"), std::string::npos) << readFile(path("go.info"));
  ASSERT_EQ(shell("lcov --summary " + path("two.info"), out), 0) << out;
  ASSERT_EQ(shell("cd " + kSource + " && genhtml -q -o " + path("html") + " " + path("two.info"), out), 0) << out;
  EXPECT_TRUE(fs::exists(fs::path(path("html")) / "index.html"));
}

TEST_F(TestCommand, HelpNamesEveryOption) {
  std::string out;
  ASSERT_EQ(test("--help", out), 0) << out;
  for (const char* option : {"--junit", "--jobs", "--filter", "--report-dir", "--backend", "--coverage", "--coverage-xml", "docs/scenarios.md"})
    EXPECT_NE(out.find(option), std::string::npos) << option << "\n" << out;
}

}  // namespace

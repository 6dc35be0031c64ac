// `--coverage` and `--coverage-xml` on `virtcom exec` and `virtcom run`, the files checked by
// Debian's lcov (`lcov --summary`) and turned into HTML by genhtml, as docs/coverage.md says.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <map>
#include <sstream>
#include <string>

#include "server_process.hpp"
#include "shell_command.hpp"
#include "support/read_file.hpp"

namespace fs = std::filesystem;

namespace {

using virtcom::e2e::ServerProcess;
using virtcom::e2e::shell;
using virtcom::test::readFile;

const std::string kExe = VIRTCOM_EXE;
const std::string kData = VIRTCOM_E2E_DATA;
// The hand-counted programs of tests/unit/coverage (their counts are checked there).
const std::string kPrograms = std::string(VIRTCOM_SOURCE_DIR) + "/tests/unit/coverage/programs";

class Coverage : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    work_ = fs::path(::testing::TempDir()) / ("virtcom_cov_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(work_);
    fs::create_directories(work_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(work_, ec);
  }
  std::string path(const std::string& name) const { return (work_ / name).string(); }
  // `virtcom ARGS` run in the programs' folder (so the tracefile names them relative to it).
  int virtcom(const std::string& args, std::string& out) const {
    return shell("cd '" + kPrograms + "' && '" + kExe + "' " + args, out);
  }
  fs::path work_;
};

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST_F(Coverage, ExecWritesATracefileLcovAndGenhtmlAccept) {
  std::string out;
  ASSERT_EQ(virtcom("exec main.st chart.st --cycles 4 --coverage '" + path("c.info") + "' --coverage-xml '" +
                        path("c.xml") + "'",
                    out),
            0)
      << out;
  // The per-POU summary on stderr.
  EXPECT_TRUE(contains(out, "Coverage  lines")) << out;
  EXPECT_TRUE(contains(out, "MAIN      8/11 72.7%        4/7 57.1%")) << out;
  const std::string info = readFile(path("c.info"));
  EXPECT_TRUE(contains(info, "SF:main.st\n")) << info;
  EXPECT_TRUE(contains(info, "BRDA:17,0,1,0\n")) << info;  // the ELSE that never runs
  EXPECT_TRUE(contains(readFile(path("c.xml")), "<class name=\"MAIN\" filename=\"main.st\"")) << readFile(path("c.xml"));

  std::string summary;
  ASSERT_EQ(shell("lcov --rc lcov_branch_coverage=1 --summary '" + path("c.info") + "'", summary), 0) << summary;
  EXPECT_TRUE(contains(summary, "lines......: 70.0% (14 of 20 lines)")) << summary;
  EXPECT_TRUE(contains(summary, "functions..: 100.0% (3 of 3 functions)")) << summary;
  EXPECT_TRUE(contains(summary, "branches...: 57.1% (4 of 7 branches)")) << summary;
  std::string html;
  ASSERT_EQ(shell("cd '" + kPrograms + "' && genhtml --branch-coverage -q -o '" + path("html") + "' '" + path("c.info") + "'", html),
            0)
      << html;
  EXPECT_TRUE(fs::exists(work_ / "html" / "index.html"));
}

TEST_F(Coverage, TracefilesOfTwoRunsMergeWithLcov) {
  std::string out;
  ASSERT_EQ(virtcom("exec main.st chart.st --backend interp --cycles 1 --coverage '" + path("a.info") + "'", out), 0) << out;
  ASSERT_EQ(virtcom("exec main.st chart.st --backend aot --cycles 3 --coverage '" + path("b.info") + "'", out), 0) << out;
  ASSERT_EQ(shell("lcov -q -a '" + path("a.info") + "' -a '" + path("b.info") + "' -o '" + path("ab.info") + "'", out), 0)
      << out;
  EXPECT_TRUE(contains(readFile(path("ab.info")), "DA:16,4\n")) << readFile(path("ab.info"));  // n := n + 1
}

TEST_F(Coverage, RunOfACellWritesCoverageAndEndsAsWithout) {
  const std::string run = "cd '" + kData + "' && '" + kExe + "' run cells/ld_handshake.yaml --quiet";
  std::string plain, covered;
  const int plainExit = shell(run, plain);
  EXPECT_EQ(shell(run + " --coverage '" + path("run.info") + "'", covered), plainExit) << covered;
  const std::string info = readFile(path("run.info"));
  EXPECT_TRUE(contains(info, "SF:cells/edge_counter.st\n")) << info;
  EXPECT_TRUE(contains(info, "end_of_record\n")) << info;
  std::string summary;
  EXPECT_EQ(shell("lcov --summary '" + path("run.info") + "'", summary), 0) << summary;
}

// "DA:LINE,COUNT" of a tracefile: LINE -> COUNT.
std::map<int, long> lineCounts(const std::string& info) {
  std::map<int, long> counts;
  std::istringstream in(info);
  for (std::string line; std::getline(in, line);)
    if (line.starts_with("DA:")) counts[std::stoi(line.substr(3))] = std::stol(line.substr(line.find(',') + 1));
  return counts;
}

// `run --hmi --coverage` with a reset from the page after the run ended: the reset is accepted
// (the fresh program is compiled with the probes too) and the tracefile counts both runs, each
// once: every line twice as often as in one run (stepped every tick, as a paced run is).
TEST_F(Coverage, AnHmiResetNeitherLosesNorDoublesCounts) {
  std::string out;
  ASSERT_EQ(shell("cd '" + kData + "' && '" + kExe + "' run cells/ld_handshake.yaml --quiet --time-mode tick --coverage '" +
                      path("one.info") + "'",
                  out),
            0)
      << out;
  ServerProcess run(kExe, {"run", "cells/ld_handshake.yaml", "--quiet", "--hmi", "127.0.0.1:0", "--speed", "20", "--coverage", path("two.info")},
                    kData, "hmi: serving http://");
  ASSERT_GT(run.port(), 0) << run.errorOutput();
  const std::string ended = "hmi: the run has ended";
  ASSERT_TRUE(run.waitForCount(ended, 1)) << run.errorOutput();
  const std::string reset = "node -e \"fetch('http://127.0.0.1:" + std::to_string(run.port()) +
                            "/api/control', {method: 'POST', body: JSON.stringify({action: 'reset'})})"
                            ".then((r) => process.exit(r.status === 200 ? 0 : 1))\"";
  ASSERT_EQ(shell(reset, out), 0) << out;
  ASSERT_TRUE(run.waitForCount(ended, 2)) << run.errorOutput();
  EXPECT_TRUE(contains(run.errorOutput(), "hmi: reset: the run starts again")) << run.errorOutput();
  run.stop();
  const auto one = lineCounts(readFile(path("one.info"))), two = lineCounts(readFile(path("two.info")));
  ASSERT_FALSE(one.empty());
  ASSERT_EQ(one.size(), two.size()) << readFile(path("two.info"));
  for (const auto& [line, count] : one) EXPECT_EQ(two.at(line), 2 * count) << "line " << line;
}

TEST_F(Coverage, HelpNamesTheOptionsAndAnUnwritableFileFails) {
  std::string out;
  ASSERT_EQ(virtcom("exec --help", out), 0);
  EXPECT_TRUE(contains(out, "--coverage")) << out;
  EXPECT_TRUE(contains(out, "--coverage-xml")) << out;
  out.clear();
  ASSERT_EQ(virtcom("run --help", out), 0);
  EXPECT_TRUE(contains(out, "--coverage")) << out;
  out.clear();
  EXPECT_NE(virtcom("exec main.st --coverage /nonexistent/dir/c.info", out), 0);
  EXPECT_TRUE(contains(out, "error: cannot write /nonexistent/dir/c.info")) << out;
}

}  // namespace

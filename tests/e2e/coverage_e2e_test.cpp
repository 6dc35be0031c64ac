// `--coverage` and `--coverage-xml` on `virtcom exec` and `virtcom run`, the files checked by
// Debian's lcov (`lcov --summary`) and turned into HTML by genhtml, as docs/coverage.md says.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "shell_command.hpp"
#include "support/read_file.hpp"

namespace fs = std::filesystem;

namespace {

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

// End-to-end: `virtcom run` on every cell in examples/drives (make test runs them). Each cell's
// PLC program runs its axis forward and backward at 50 % and recovers from an injected fault;
// the recorded PLC variables (CSV) and the JSON report are checked.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace {

const std::string kExamples = std::string(VIRTCOM_SOURCE_DIR) + "/examples/drives";

struct Run {
  int exitCode = -1;
  std::string out, csv, json;
};

std::string readFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

Run runCell(const std::string& cell) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("virtcom_drives_e2e_" + cell + "_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  Run r;
  const std::string cmd = std::string(VIRTCOM_EXE) + " run " + kExamples + "/" + cell + "/cell.yaml --quiet --csv " +
                          (dir / "run.csv").string() + " --json " + (dir / "run.json").string() + " 2>&1";
  FILE* p = ::popen(cmd.c_str(), "r");
  char buf[4096];
  size_t n = 0;
  while (p && (n = std::fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
  const int status = p ? ::pclose(p) : -1;
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.csv = readFile(dir / "run.csv");
  r.json = readFile(dir / "run.json");
  fs::remove_all(dir);
  return r;
}

// The last value the CSV records for `signal`, NaN if none.
double lastValue(const std::string& csv, const std::string& signal) {
  double value = NAN;
  std::istringstream in(csv);
  for (std::string line; std::getline(in, line);) {
    const size_t a = line.find(',');
    const size_t b = line.find(',', a + 1);
    if (a == std::string::npos || b == std::string::npos || line.substr(a + 1, b - a - 1) != signal) continue;
    value = std::stod(line.substr(b + 1));
  }
  return value;
}

void expectCompletedTest(const Run& r, double expectedRpm, const std::string& faultText) {
  ASSERT_EQ(r.exitCode, 0) << r.out;
  EXPECT_NE(r.json.find("\"end\": \"completed\""), std::string::npos) << r.json.substr(0, 400);
  EXPECT_NEAR(lastValue(r.csv, "MAIN.forwardRpm"), expectedRpm, 1.0);
  EXPECT_NEAR(lastValue(r.csv, "MAIN.backwardRpm"), -expectedRpm, 1.0);
  EXPECT_EQ(lastValue(r.csv, "MAIN.faultsSeen"), 1.0);
  EXPECT_EQ(lastValue(r.csv, "MAIN.phase"), 4.0);
  EXPECT_NE(r.json.find(faultText), std::string::npos);
  EXPECT_LT(std::abs(lastValue(r.csv, "Drive1.speed")), 2.0);  // stopped (within one N2 count) at the end
  EXPECT_NE(lastValue(r.csv, "Drive1.position"), 0.0);          // the load moved
}

TEST(DriveExamples, G120Telegram1RunsRecoversFromF07900AndStops) {
  expectCompletedTest(runCell("g120"), 675.0, "F07900");  // 50 % of p2000 = 1350 rpm
}

TEST(DriveExamples, PowerFlex525RunsRecoversFromCommLossAndStops) {
  expectCompletedTest(runCell("pf525"), 712.8, "F83");    // 50 % of 1425 rpm = 1188 x 0.01 Hz
}

TEST(DriveExamples, WordArrayWiringRunsTheDrive) {
  const std::string cmd = std::string(VIRTCOM_EXE) + " run " + VIRTCOM_SOURCE_DIR +
                          "/tests/e2e/data/drives_word_array/cell.yaml --quiet --json /dev/stdout 2>&1";
  FILE* p = ::popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::string out;
  char buf[4096];
  for (size_t n; (n = std::fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
  ASSERT_EQ(::pclose(p), 0) << out;
  EXPECT_NE(out.find("'MAIN.running' became true"), std::string::npos) << out;
}

}  // namespace

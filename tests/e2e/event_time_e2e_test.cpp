// Event-driven time is exact: every runnable cell of examples/ and tests/e2e/data (the golden
// gearbox runs included, every operation sequence) is run by the built binary (VIRTCOM_EXE) with
// `--time-mode tick` and `--time-mode event`, and everything the run writes is compared byte for
// byte: exit code, summary, JSON, HTML, VCD and CSV. The only parts allowed to differ are the
// ones that say how the clock went: the JSON's `run.time` object and the summary's
// "Event time" line. Cells whose controller is another process (`plc: modbus:`/`plc: ads:`,
// examples/*/bridge.yaml) need a peer and never jump (bridges write from outside); they are left out.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "shell_command.hpp"
#include "support/read_file.hpp"

namespace fs = std::filesystem;

namespace {

using virtcom::test::readFile;

const char* const kExe = VIRTCOM_EXE;
const fs::path kSource = VIRTCOM_SOURCE_DIR;

struct Case {
  std::string name;  // readable, unique (the ctest case name)
  fs::path cell;
  std::string args;  // extra command-line arguments, e.g. --set MAIN.sequence=2
};

// A cell whose `plc:` is another process reached over Modbus, ADS or OPC UA (examples/*/bridge.yaml, opcua-bridge.yaml).
bool needsPeer(const fs::path& cell) {
  return std::regex_search(readFile(cell), std::regex(R"(\nplc:[^\n]*\n([ \t]+[^\n]*\n)*?[ \t]+(modbus|ads|opcua):)"));
}

std::string caseName(const fs::path& cell) {
  std::string name = fs::relative(cell, kSource).replace_extension("").string();
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

std::vector<Case> discover() {
  std::vector<Case> cases;
  std::vector<fs::path> cells;
  for (const fs::path& root : {kSource / "examples", kSource / "tests" / "e2e" / "data"})
    for (const auto& e : fs::recursive_directory_iterator(root))
      if (e.is_regular_file() && e.path().extension() == ".yaml" && readFile(e.path()).find("\ndevices:") != std::string::npos &&
          !needsPeer(e.path()))
        cells.push_back(e.path());
  std::sort(cells.begin(), cells.end());
  for (const fs::path& cell : cells) {
    cases.push_back({caseName(cell), cell, ""});
    // The gearbox cells choose their operation sequence (tests/golden/cells: sequences 1-4).
    if (cell.parent_path().filename() == "gearbox-cell")
      for (int seq = 1; seq <= 4; ++seq)
        cases.push_back({caseName(cell) + "_seq" + std::to_string(seq), cell, "--set MAIN.sequence=" + std::to_string(seq)});
  }
  return cases;
}

struct Outputs {
  int exitCode = -1;
  std::string console, json, html, vcd, csv;
};

// Drops the lines that report how the clock went (they differ between the modes by design).
std::string withoutTimeReport(const std::string& text) {
  std::istringstream in(text);
  std::string line, out;
  bool inTime = false;
  while (std::getline(in, line)) {
    if (line.find("\"time\": {") != std::string::npos) {
      inTime = true;
    } else if (inTime) {
      inTime = line.find('}') == std::string::npos;
    } else if (line.rfind("Event time ", 0) != 0) {
      out += line + "\n";
    }
  }
  return out;
}

Outputs run(const Case& c, const std::string& mode) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("evt_" + c.name + "_" + mode);
  fs::create_directories(dir);
  Outputs o;
  const std::string files = " --json " + (dir / "r.json").string() + " --report " + (dir / "r.html").string() + " --vcd " +
                            (dir / "r.vcd").string() + " --csv " + (dir / "r.csv").string();
  o.exitCode = virtcom::e2e::shell("cd " + c.cell.parent_path().string() + " && " + kExe + " run " + c.cell.string() + " " +
                                       c.args + files + " --time-mode " + mode,
                                   o.console);
  o.json = readFile(dir / "r.json");
  o.html = readFile(dir / "r.html");
  o.vcd = readFile(dir / "r.vcd");
  o.csv = readFile(dir / "r.csv");
  return o;
}

class EventTime : public ::testing::TestWithParam<Case> {};

TEST_P(EventTime, SameOutputsAsSteppingEveryTick) {
  const Case& c = GetParam();
  const Outputs tick = run(c, "tick"), event = run(c, "event");
  EXPECT_EQ(event.exitCode, tick.exitCode);
  EXPECT_EQ(withoutTimeReport(event.console), withoutTimeReport(tick.console));
  EXPECT_EQ(withoutTimeReport(event.json), withoutTimeReport(tick.json));
  EXPECT_TRUE(event.html == tick.html) << "HTML reports differ";
  EXPECT_TRUE(event.vcd == tick.vcd) << "VCD files differ";
  EXPECT_TRUE(event.csv == tick.csv) << "CSV files differ";
  // In tick mode nothing is skipped, whatever the cell.
  if (!tick.json.empty()) EXPECT_NE(tick.json.find("\"ticks_skipped\": 0,"), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(Cells, EventTime, ::testing::ValuesIn(discover()),
                         [](const ::testing::TestParamInfo<Case>& info) { return info.param.name; });

// The equivalence above proves nothing if nothing jumps: the gearbox (robots waiting on the
// press and each other), the conveyor activity diagram (waiting for parts to arrive) and a
// ladder handshake with a timed device must skip ticks, and the summary says how many.
TEST(EventTimeJumps, IdleCellsSkipTicksAndSayHowMany) {
  for (const char* cell : {"examples/gearbox-cell/cell.yaml", "examples/activity/conveyor-cell.yaml",
                           "tests/e2e/data/cells/ld_handshake.yaml"}) {
    const Case c{caseName(kSource / cell), kSource / cell, ""};
    const Outputs event = run(c, "event");
    EXPECT_NE(event.json.find("\"mode\": \"event\""), std::string::npos) << cell;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(event.json, m, std::regex(R"("ticks_skipped": (\d+))"))) << cell;
    EXPECT_GT(std::stoull(m[1]), 0u) << cell;
    EXPECT_NE(event.console.find("Event time    " + m[1].str() + " of "), std::string::npos) << event.console;
  }
}

TEST(EventTimeOption, RejectsAnUnknownMode) {
  std::string out;
  const int code = virtcom::e2e::shell(std::string(kExe) + " run " + (kSource / "examples/gearbox-cell/cell.yaml").string() +
                                           " --time-mode sometimes",
                                       out);
  EXPECT_EQ(code, 64) << out;
  EXPECT_NE(out.find("--time-mode"), std::string::npos) << out;
}

}  // namespace

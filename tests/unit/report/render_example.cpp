// Renders the example assembly-cell Trace with every report writer, for looking at the output
// (tests/e2e/report_render_check.sh screenshots the HTML).
//   report_render_example [OUT_DIR] [--long CYCLES] [--cycle-only]
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "example_trace.hpp"
#include "report/html_report.hpp"
#include "report/json_report.hpp"
#include "report/kpis.hpp"
#include "report/summary.hpp"
#include "report/waveform.hpp"

using namespace virtcom;
using namespace virtcom::report;

int main(int argc, char** argv) {
  std::filesystem::path dir = "/tmp/virtcom-report";
  int cycles = 0;
  bool cycleOnly = false;
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    if (arg == "--long" && i + 1 < argc) cycles = std::atoi(argv[++i]);
    else if (arg == "--cycle-only") cycleOnly = true;
    else dir = arg;
  }
  Trace trace = cycles > 0 ? testing::longRunTrace(cycles) : testing::exampleCellTrace();
  Kpis kpis = computeKpis(trace);
  HtmlOptions options;
  options.title = "Gearbox assembly cell";
  options.subtitle = cycles > 0 ? "example trace, " + std::to_string(cycles) + " cycles" : "example trace";
  options.cycleOnly = cycleOnly;
  options.signals = {"PLC.start", "Robot1.busy", "Press.force", "TableX.pos", "Robot2.error", "Cell.recipe"};

  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  auto write = [&](const char* name, const std::string& text) {
    std::ofstream out(dir / name, std::ios::binary);
    out << text;
    if (!out) {
      std::cerr << "cannot write " << (dir / name).string() << "\n";
      std::exit(1);
    }
    std::cout << (dir / name).string() << " (" << text.size() << " bytes)\n";
  };
  write("report.html", htmlReport(trace, kpis, options));
  write("report.json", jsonReport(trace, kpis));
  write("report.vcd", vcdReport(trace));
  write("changes.csv", csvChanges(trace));
  write("summary.txt", summaryTable(trace, kpis));
  return 0;
}

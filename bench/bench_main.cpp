// virtcom_bench's entry point: Google Benchmark's usual flags and output, followed by a
// summary of the VM/native ratio for every case that has both a `<case>/vm` and a
// `<case>/native` benchmark, so both sides come from the same run of the same binary.
// The ratio uses CPU time per iteration: on a shared machine (other builds running) real time
// also counts the time the thread waited for a core, which says nothing about either side.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <ostream>
#include <string>
#include <vector>

namespace {

// Forwards everything to the default display reporter (so --benchmark_counters_tabular,
// --benchmark_format and colour behave as usual) and remembers the CPU time per iteration of
// each benchmark: the median aggregate when repetitions are used, else the single run.
class RatioReporter final : public benchmark::BenchmarkReporter {
 public:
  // `display` is not owned (CreateDefaultDisplayReporter's object lives for the whole run).
  explicit RatioReporter(benchmark::BenchmarkReporter* display) : display_(display) {}

  bool ReportContext(const Context& context) override { return display_->ReportContext(context); }

  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      if (run.error_occurred) continue;
      const bool isMedian = run.run_type == Run::RT_Aggregate && run.aggregate_name == "median";
      if (run.run_type == Run::RT_Aggregate && !isMedian) continue;
      const std::string name = run.run_name.str();
      const double ns = run.GetAdjustedCPUTime() * (1e9 / benchmark::GetTimeUnitMultiplier(run.time_unit));
      if (isMedian || !haveMedian_[name]) nsPerIteration_[name] = ns;
      if (isMedian) haveMedian_[name] = true;
    }
    display_->ReportRuns(runs);
  }

  void Finalize() override {
    display_->Finalize();
    std::ostream& out = GetOutputStream();
    char line[128];
    bool header = false;
    for (const auto& [name, vmNs] : nsPerIteration_) {
      const auto slash = name.rfind("/vm");
      if (slash == std::string::npos || slash + 3 != name.size()) continue;
      const std::string caseName = name.substr(0, slash);
      const auto native = nsPerIteration_.find(caseName + "/native");
      if (native == nsPerIteration_.end() || native->second <= 0) continue;
      if (!header) {
        std::snprintf(line, sizeof line, "\nVM/native, CPU time per scan\n%-12s %14s %14s %10s\n", "case",
                      "vm ns", "native ns", "vm/native");
        out << line;
        header = true;
      }
      std::snprintf(line, sizeof line, "%-12s %14.1f %14.1f %9.1fx\n", caseName.c_str(), vmNs,
                    native->second, vmNs / native->second);
      out << line;
    }
    out.flush();
  }

 private:
  benchmark::BenchmarkReporter* display_;
  std::map<std::string, double> nsPerIteration_;
  std::map<std::string, bool> haveMedian_;
};

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  RatioReporter reporter(benchmark::CreateDefaultDisplayReporter());
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  return 0;
}

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
// each benchmark: with repetitions the "min" aggregate (see withMinStatistic), else the median,
// else the single run.
class RatioReporter final : public benchmark::BenchmarkReporter {
 public:
  // `display` is not owned (CreateDefaultDisplayReporter's object lives for the whole run).
  explicit RatioReporter(benchmark::BenchmarkReporter* display) : display_(display) {}

  bool ReportContext(const Context& context) override { return display_->ReportContext(context); }

  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      if (run.error_occurred) continue;
      int rank = 0;  // a better statistic replaces a worse one
      if (run.run_type == Run::RT_Aggregate) {
        if (run.aggregate_name == "min") rank = 2;
        else if (run.aggregate_name == "median") rank = 1;
        else continue;
      }
      const std::string name = run.run_name.str();
      const double ns = run.GetAdjustedCPUTime() * (1e9 / benchmark::GetTimeUnitMultiplier(run.time_unit));
      auto [it, inserted] = best_.try_emplace(name, Entry{rank, ns});
      if (!inserted && rank >= it->second.rank) it->second = Entry{rank, ns};
    }
    display_->ReportRuns(runs);
  }

  void Finalize() override {
    display_->Finalize();
    // Only under the console table: JSON/CSV output must stay machine-readable.
    if (dynamic_cast<benchmark::ConsoleReporter*>(display_) == nullptr) return;
    std::ostream& out = GetOutputStream();
    char line[128];
    bool header = false;
    for (const auto& [name, vm] : best_) {
      const auto slash = name.rfind("/vm");
      if (slash == std::string::npos || slash + 3 != name.size()) continue;
      const std::string caseName = name.substr(0, slash);
      const auto native = best_.find(caseName + "/native");
      if (native == best_.end() || native->second.ns <= 0) continue;
      if (!header) {
        std::snprintf(line, sizeof line, "\nVM/native, CPU time per scan (min over repetitions if any)\n%-12s %14s %14s %10s\n", "case",
                      "vm ns", "native ns", "vm/native");
        out << line;
        header = true;
      }
      std::snprintf(line, sizeof line, "%-12s %14.1f %14.1f %9.1fx\n", caseName.c_str(), vm.ns,
                    native->second.ns, vm.ns / native->second.ns);
      out << line;
    }
    out.flush();
  }

 private:
  struct Entry {
    int rank;  // 0 single run, 1 median, 2 min
    double ns;
  };
  benchmark::BenchmarkReporter* display_;
  std::map<std::string, Entry> best_;
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

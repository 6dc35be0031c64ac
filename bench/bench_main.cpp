// virtcom_bench's entry point: Google Benchmark's usual flags and output, followed by a
// summary of the interpreter/native and AOT/native ratios for every case that has a
// `<case>/native` benchmark and a `<case>/vm` or `<case>/aot` one, so all sides come from the
// same run of the same binary.
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
    char line[160];
    bool header = false;
    for (const auto& [name, native] : best_) {
      const auto slash = name.rfind("/native");
      if (slash == std::string::npos || slash + 7 != name.size() || native.ns <= 0) continue;
      const std::string caseName = name.substr(0, slash);
      const auto vm = best_.find(caseName + "/vm");
      const auto aot = best_.find(caseName + "/aot");
      if (vm == best_.end() && aot == best_.end()) continue;
      if (!header) {
        std::snprintf(line, sizeof line,
                      "\nVM/native, CPU time per scan (min over repetitions if any)\n%-12s %12s %12s %12s %10s %10s\n",
                      "case", "vm ns", "aot ns", "native ns", "vm/native", "aot/native");
        out << line;
        header = true;
      }
      const auto ns = [&](auto it, char* buf, size_t size) {
        if (it == best_.end()) std::snprintf(buf, size, "%s", "-");
        else std::snprintf(buf, size, "%.1f", it->second.ns);
      };
      const auto ratio = [&](auto it, char* buf, size_t size) {
        if (it == best_.end()) std::snprintf(buf, size, "%s", "-");
        else std::snprintf(buf, size, "%.1fx", it->second.ns / native.ns);
      };
      char vmNs[24], aotNs[24], vmRatio[24], aotRatio[24];
      ns(vm, vmNs, sizeof vmNs);
      ns(aot, aotNs, sizeof aotNs);
      ratio(vm, vmRatio, sizeof vmRatio);
      ratio(aot, aotRatio, sizeof aotRatio);
      std::snprintf(line, sizeof line, "%-12s %12s %12s %12.1f %10s %10s\n", caseName.c_str(), vmNs, aotNs, native.ns,
                    vmRatio, aotRatio);
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

// Evaluations per hour of `virtcom optimise` on the gearbox (issue 19's goal: at least 100,000):
// the refined sequence's job list evaluated again and again as the optimiser does it (a fresh
// cell from the compiled template, the list written, one cycle simulated), on 1 thread and in
// batches of 16 on 2 threads, and a whole exhaustive search of the gearbox model (24 candidates).
#include <benchmark/benchmark.h>

#include "optimize/evaluator.hpp"
#include "optimize/search.hpp"

namespace virtcom::bench {
namespace {

struct Gearbox {
  SourceManager sources;
  Diagnostics diags;
  std::optional<optimize::ProcessModel> model;
  std::unique_ptr<optimize::Evaluator> evaluator;
  Gearbox() {
    model = optimize::readProcessModel(VIRTCOM_SOURCE_DIR "/examples/gearbox-cell/process.yaml", sources, diags);
    if (model) evaluator = optimize::Evaluator::create(*model, sources, diags);
  }
};

Gearbox& gearbox() {
  static Gearbox g;
  return g;
}

void BM_GearboxEvaluations(benchmark::State& state) {
  Gearbox& g = gearbox();
  if (!g.evaluator) {
    state.SkipWithError(g.diags.render(g.sources).c_str());
    return;
  }
  const unsigned threads = static_cast<unsigned>(state.range(0));
  const std::vector<optimize::JobList> batch(16, optimize::buildJobList(*g.model, g.model->sequences[2].candidate));
  for (auto _ : state) benchmark::DoNotOptimize(optimize::evaluateAll(*g.evaluator, batch, threads));
  state.counters["evals"] = benchmark::Counter(16.0 * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);  // per second
}
BENCHMARK(BM_GearboxEvaluations)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_GearboxExhaustiveSearch(benchmark::State& state) {
  Gearbox& g = gearbox();
  if (!g.evaluator) {
    state.SkipWithError(g.diags.render(g.sources).c_str());
    return;
  }
  optimize::BatchEvaluator batch = [&](const std::vector<optimize::JobList>& b) { return optimize::evaluateAll(*g.evaluator, b, 2); };
  for (auto _ : state) {
    optimize::SearchOptions o;
    o.budgetEvals = 100;
    benchmark::DoNotOptimize(optimize::search(*g.model, batch, o));
  }
}
BENCHMARK(BM_GearboxExhaustiveSearch)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace virtcom::bench

BENCHMARK_MAIN();

// Evaluations per hour of `virtcom optimise` (issue 19's goal: at least 100,000 on the gearbox):
// the gearbox's refined job list evaluated again and again as the optimiser does it (a fresh
// cell from the compiled template, the list written, one cycle simulated), on 1 thread and in
// batches of 16 on 2 threads; a whole exhaustive search of the gearbox model (24 candidates);
// and annealing on the larger line of bench/optimise/ (over a thousand candidates), whose
// evaluations per second are what a search of a real model reaches (docs/scaling.md).
#include <benchmark/benchmark.h>

#include "optimize/evaluator.hpp"
#include "optimize/search.hpp"

namespace virtcom::bench {
namespace {

struct Model {
  SourceManager sources;
  Diagnostics diags;
  std::optional<optimize::ProcessModel> model;
  std::unique_ptr<optimize::Evaluator> evaluator;
  explicit Model(const char* path) {
    model = optimize::readProcessModel(path, sources, diags);
    if (model) evaluator = optimize::Evaluator::create(*model, sources, diags);
  }
  // False (the benchmark skipped with the model's mistakes) when it did not load.
  bool ready(benchmark::State& state) {
    if (!evaluator) state.SkipWithError(diags.render(sources).c_str());
    return evaluator != nullptr;
  }
};

Model& gearbox() {
  static Model m(VIRTCOM_SOURCE_DIR "/examples/gearbox-cell/process.yaml");
  return m;
}

Model& line() {
  static Model m(VIRTCOM_SOURCE_DIR "/bench/optimise/line_model.yaml");
  return m;
}

void BM_GearboxEvaluations(benchmark::State& state) {
  Model& g = gearbox();
  if (!g.ready(state)) return;
  const unsigned threads = static_cast<unsigned>(state.range(0));
  const std::vector<optimize::JobList> batch(16, optimize::buildJobList(*g.model, g.model->sequences[2].candidate));
  for (auto _ : state) benchmark::DoNotOptimize(optimize::evaluateAll(*g.evaluator, batch, threads));
  state.counters["evals"] = benchmark::Counter(16.0 * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);  // per second
}
BENCHMARK(BM_GearboxEvaluations)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_GearboxExhaustiveSearch(benchmark::State& state) {
  Model& g = gearbox();
  if (!g.ready(state)) return;
  optimize::BatchEvaluator batch = [&](const std::vector<optimize::JobList>& b) { return optimize::evaluateAll(*g.evaluator, b, 2); };
  for (auto _ : state) {
    optimize::SearchOptions o;
    o.budgetEvals = 100;
    benchmark::DoNotOptimize(optimize::search(*g.model, batch, o));
  }
}
BENCHMARK(BM_GearboxExhaustiveSearch)->Unit(benchmark::kMillisecond)->UseRealTime();

// 256 annealing evaluations of the line on 1 or 2 threads: evals/s of a search, not of one list.
void BM_LineAnneal(benchmark::State& state) {
  Model& l = line();
  if (!l.ready(state)) return;
  const unsigned threads = static_cast<unsigned>(state.range(0));
  optimize::BatchEvaluator batch = [&](const std::vector<optimize::JobList>& b) { return optimize::evaluateAll(*l.evaluator, b, threads); };
  uint64_t evaluations = 0;
  for (auto _ : state) {
    optimize::SearchOptions o;
    o.budgetEvals = 256;
    o.method = optimize::Method::Anneal;
    evaluations += optimize::search(*l.model, batch, o).evaluations;
  }
  state.counters["evals"] = benchmark::Counter(static_cast<double>(evaluations), benchmark::Counter::kIsRate);  // per second
}
BENCHMARK(BM_LineAnneal)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace virtcom::bench

BENCHMARK_MAIN();

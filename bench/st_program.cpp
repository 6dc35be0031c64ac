#include "st_program.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "aot/compile.hpp"
#include "core/diagnostics.hpp"
#include "core/source.hpp"
#include "lang/st/compiler.hpp"

#ifndef VIRTCOM_BENCH_DIR
#error "VIRTCOM_BENCH_DIR must name the directory of the benchmark ST programs"
#endif

namespace virtcom::bench {

StProgram::StProgram(std::string_view fileName, Backend backend, bool coverage) {
  const std::string path = std::string(VIRTCOM_BENCH_DIR) + "/" + std::string(fileName);
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    error_ = "cannot read " + path;
    return;
  }
  std::stringstream text;
  text << in.rdbuf();
  SourceManager sources;
  Diagnostics diags;
  module_ = st::compileProgram({st::SourceInput{path, text.str()}}, sources, diags, st::coverageOptions(coverage));
  if (!module_) {
    error_ = "compile error:\n" + diags.render(sources);
    return;
  }
  bool found = false;
  for (const auto& p : module_->programs) {
    if (p.name == "MAIN") {
      mainPou_ = p.pou;
      mainAddress_ = p.address;
      found = true;
    }
  }
  if (!found) {
    error_ = path + ": no program instance MAIN";
    return;
  }
  // Every iteration must execute the scan: the arith, bits and strings programs repeat
  // themselves exactly, so a runtime that skips repeated scans would measure nothing.
  plc::RuntimeOptions options;
  options.skipRepeatedScans = false;
  runtime_ = std::make_unique<plc::Runtime>(*module_, clock_, options);
  runtime_->machine().countInstructions(true);  // the vm_instr counters (the timings include the count)
  if (backend == Backend::Aot) {
    aot::CompileResult compiled = aot::compileModule(*module_);
    if (!compiled.code) {
      error_ = "AOT backend: " + compiled.error;
      return;
    }
    runtime_->machine().useCompiled(compiled.code);
  }
  if (!runtime_->coldStart()) error_ = "cold start fault: " + runtime_->faultText();
}

bool StProgram::scan() {
  if (runtime_->tick()) return true;
  const std::string fault = runtime_->faultText();
  error_ = fault.empty() ? "the PLC is not in RUN" : "runtime fault: " + fault;
  return false;
}

bool StProgram::runMain(int64_t nowNs) {
  vm::Machine& machine = runtime_->machine();
  machine.setTaskTimeNs(nowNs);
  if (machine.run(mainPou_, mainAddress_)) return true;
  error_ = "runtime fault: " + machine.fault().describe(*module_);
  return false;
}

std::string StProgram::text(std::string_view path) const {
  auto ref = bc::resolveVariable(*module_, path);
  if (!ref) return "<unknown path>";
  return bc::formatValue(*module_, *ref, runtime_->machine().memory());
}

bool warmUp(benchmark::State& state, StProgram& prog, int scans) {
  for (int i = 0; prog.ok() && i < scans; ++i) prog.scan();
  if (prog.ok()) return true;
  state.SkipWithError(prog.error().c_str());
  return false;
}

bool expectString(benchmark::State& state, const StProgram& prog, std::string_view path, std::string_view want) {
  const std::string got = prog.text(path);
  const std::string literal = "'" + std::string(want) + "'";
  if (got == literal) return true;
  const std::string msg =
      "ST result differs from the C++ twin: " + std::string(path) + " = " + got + ", twin = " + literal;
  state.SkipWithError(msg.c_str());
  return false;
}

void measureScans(benchmark::State& state, StProgram& prog) {
  const uint64_t before = prog.instructionsExecuted();
  for (auto _ : state) {
    if (!prog.scan()) {
      state.SkipWithError(prog.error().c_str());
      break;
    }
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));
  state.counters["vm_instr"] = benchmark::Counter(static_cast<double>(prog.instructionsExecuted() - before),
                                                  benchmark::Counter::kAvgIterations);
}

void measureMachineRuns(benchmark::State& state, StProgram& prog) {
  constexpr int64_t kScanNs = 10'000'000;
  int64_t nowNs = prog.runtime().nextTickNs();
  const uint64_t before = prog.instructionsExecuted();
  for (auto _ : state) {
    if (!prog.runMain(nowNs)) {
      state.SkipWithError(prog.error().c_str());
      break;
    }
    nowNs += kScanNs;
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));
  state.counters["vm_instr"] = benchmark::Counter(static_cast<double>(prog.instructionsExecuted() - before),
                                                  benchmark::Counter::kAvgIterations);
}

void withMinStatistic(benchmark::internal::Benchmark* b) {
  b->ComputeStatistics("min", [](const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); });
}

void reportNative(benchmark::State& state) {
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));
  state.counters["vm_instr"] = 0;
}

}  // namespace virtcom::bench

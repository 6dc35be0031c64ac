#pragma once
// Evaluating candidates by simulation: the real PLC program on the real cell model. The cell file
// is read and its PLC program compiled once (cell::CellTemplate); every evaluation builds a fresh
// cell from it (devices, world and bus in their initial state, a copy of the compiled program),
// writes the job list into the PLC's memory before the first scan and runs one assembly cycle.
// Nothing is compiled per candidate. evaluate() is const and thread-safe: one simulation per
// calling thread; evaluateAll() spreads a batch over threads, results in batch order, so the
// outcome does not depend on the number of threads.
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cell/cell.hpp"
#include "core/trace.hpp"
#include "optimize/job_list.hpp"
#include "optimize/process_model.hpp"

namespace virtcom::optimize {

struct Evaluation {
  bool feasible = false;
  std::string reason;     // why not feasible: collision, device error, deadlock, PLC fault, ...
  int64_t cycleNs = 0;    // the completed cycle (feasible only)
  double energyJ = 0;     // every device's energy over the run (feasible only)
  RunEnd end = RunEnd::Completed;
};

// One cycle of a fresh cell built from `tmpl` and `root` (the template's tree or an edited copy:
// `virtcom sweep`), `preset` writing into the PLC's memory before its first scan and `atEnd`
// (optional) reading it after the last; the outcome judged into `out`. Returns the finished cell
// (null if it did not load: `out.reason` says why). Thread-safe; allocates.
std::unique_ptr<cell::Cell> runInstance(const cell::CellTemplate& tmpl, const ConfigNode& root, const std::function<void(uint8_t*)>& preset,
                                        int64_t timeLimitNs, Evaluation& out, const std::function<void(const uint8_t*)>& atEnd = {});

class Evaluator {
 public:
  // Reads the model's cell, compiles its PLC program and resolves the job list's variables,
  // reporting mistakes through `diags` (the binding's at the model file, code C070). Null on an
  // error.
  static std::unique_ptr<Evaluator> create(const ProcessModel& model, SourceManager& sources, Diagnostics& diags);

  // Simulates one job list. Thread-safe. Allocates (a fresh cell per call).
  Evaluation evaluate(const JobList& list) const;
  // As evaluate(), keeping the finished cell (its trace for the HTML report).
  std::unique_ptr<cell::Cell> run(const JobList& list, Evaluation& out) const;

  // The job list variable's name inside its POU ("jobs") and its declared type.
  std::string arrayName() const;
  std::string arrayType() const;
  size_t capacity() const { return slots_.size(); }
  const ProcessModel& model() const { return model_; }

 private:
  struct Slot {
    bc::VarRef device, code;
    std::vector<bc::VarRef> waits;
  };
  Evaluator(const ProcessModel& model) : model_(model) {}
  bool resolve(Diagnostics& diags);
  void writeJobs(const JobList& list, uint8_t* memory) const;

  const ProcessModel& model_;
  std::unique_ptr<cell::CellTemplate> template_;
  std::vector<Slot> slots_;
  std::optional<bc::VarRef> count_, progress_;
  std::vector<std::pair<bc::VarRef, std::string>> presets_;
  bc::TypeId arrayTypeId_ = bc::kNoType;
};

// Calls body(0..count-1) on up to `threads` threads (the calling one included), each index once.
void parallelFor(size_t count, unsigned threads, const std::function<void(size_t)>& body);

// Evaluates every list of `batch` on up to `threads` threads; results[i] belongs to batch[i].
std::vector<Evaluation> evaluateAll(const Evaluator& evaluator, const std::vector<JobList>& batch, unsigned threads);

}  // namespace virtcom::optimize

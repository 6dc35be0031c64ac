// Candidates simulated on fresh cells built from one compiled template.
#include "optimize/evaluator.hpp"

#include <cstdio>
#include <thread>

#include "core/cell_diagnostic_codes.hpp"
#include "plant/device_errors.hpp"
#include "report/kpis.hpp"
#include "sim/simulation.hpp"

namespace virtcom::optimize {

namespace {

std::string seconds(int64_t ns) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f s", static_cast<double>(ns) * 1e-9);
  return buf;
}

}  // namespace

std::unique_ptr<cell::Cell> runInstance(const cell::CellTemplate& tmpl, const ConfigNode& root, const std::function<void(uint8_t*)>& preset,
                                        int64_t timeLimitNs, Evaluation& out, const std::function<void(const uint8_t*)>& atEnd) {
  out = {};
  SourceManager sources;
  Diagnostics diags;
  auto cell = cell::instantiateCell(tmpl, root, sources, diags);
  if (!cell) {
    out.reason = "the cell does not load: " + diags.render(sources);
    return nullptr;
  }
  sim::SimOptions options;
  options.keepAllChanges = false;
  if (timeLimitNs > 0) options.timeLimitNs = timeLimitNs;
  options.preset = [&](plc::Runtime& plc) { preset(plc.machine().memory()); };
  sim::Simulation simulation(*cell, options);
  out.end = simulation.run();
  if (atEnd) atEnd(simulation.plc().machine().memory());
  const report::Kpis kpis = report::computeKpis(cell->trace);
  const Trace& t = cell->trace;
  switch (out.end) {
    case RunEnd::Completed:
      out.feasible = kpis.collisions == 0 && kpis.errors == 0;
      if (!out.feasible) out.reason = "completed with " + std::to_string(kpis.collisions) + " collision(s), " + std::to_string(kpis.errors) + " device error(s)";
      break;
    case RunEnd::Collision: out.reason = "collision at " + seconds(t.endNs) + ": " + t.endMessage; break;
    case RunEnd::DeviceError: {
      int32_t code = 0;
      for (const auto& d : cell->devices) code = code ? code : d->errorCode();
      out.reason = "device error at " + seconds(t.endNs) + ": " + t.endMessage + " (" + plant::deviceErrorMeaning(code) + ")";
      break;
    }
    case RunEnd::TimeLimit: out.reason = "deadlock: no completed cycle within " + seconds(t.endNs); break;
    case RunEnd::PlcFault: out.reason = "PLC fault at " + seconds(t.endNs) + ": " + t.endMessage; break;
    case RunEnd::Interrupted: out.reason = "interrupted"; break;
  }
  if (out.feasible) {
    out.cycleNs = kpis.cycleTimeNs;
    out.energyJ = kpis.totalEnergyJ;
  }
  return cell;
}

std::unique_ptr<Evaluator> Evaluator::create(const ProcessModel& model, SourceManager& sources, Diagnostics& diags) {
  std::unique_ptr<Evaluator> e(new Evaluator(model));
  e->template_ = cell::loadCellTemplate(model.cellFile, sources, diags);
  if (!e->template_) return nullptr;
  if (!e->template_->module) {
    diags.error(celldiag::C070, {}, "the cell '" + model.cellFile + "' has no soft PLC ('plc: sources') to run the job lists");
    return nullptr;
  }
  if (!e->resolve(diags)) return nullptr;
  return e;
}

// Every field of every element of the job-list array, and the other variables the model names.
bool Evaluator::resolve(Diagnostics& diags) {
  const bc::Module& m = *template_->module;
  const JobListBinding& b = model_.jobList;
  auto fail = [&](const std::string& message) {
    diags.error(celldiag::C070, b.loc, "'job_list': " + message);
    return false;
  };
  auto array = bc::resolveVariable(m, b.variable);
  if (!array || m.types[array->type].kind != bc::TypeKind::Array || m.types[array->type].dims.size() != 1)
    return fail("'" + b.variable + "' is not a one-dimensional ARRAY of the PLC program");
  arrayTypeId_ = array->type;
  const bc::ArrayDim dim = m.types[array->type].dims[0];
  for (int64_t i = dim.lo; i <= dim.hi; ++i) {
    const std::string element = b.variable + "[" + std::to_string(i) + "].";
    Slot s;
    auto device = bc::resolveVariable(m, element + b.deviceField);
    auto code = bc::resolveVariable(m, element + b.codeField);
    if (!device || !code) return fail("'" + b.variable + "' has no fields '" + b.deviceField + "' and '" + b.codeField + "'");
    s.device = *device;
    s.code = *code;
    for (const std::string& w : b.waitFields) {
      auto wait = bc::resolveVariable(m, element + w);
      if (!wait) return fail("'" + b.variable + "' has no field '" + w + "' (a wait field)");
      s.waits.push_back(*wait);
    }
    slots_.push_back(std::move(s));
  }
  std::vector<uint8_t> scratch(m.memorySize(), 0);
  for (const auto& [name, value] : b.presets) {
    auto ref = bc::resolveVariable(m, name);
    if (!ref) return fail("'set': the PLC has no variable '" + name + "'");
    if (std::string problem = bc::writeValueFromText(m, *ref, value, scratch.data()); !problem.empty())
      return fail("'set': " + name + ": " + problem);
    presets_.emplace_back(*ref, value);
  }
  if (!b.count.empty() && !(count_ = bc::resolveVariable(m, b.count))) return fail("'count': the PLC has no variable '" + b.count + "'");
  if (!b.progress.empty() && !(progress_ = bc::resolveVariable(m, b.progress)))
    return fail("'progress': the PLC has no variable '" + b.progress + "'");
  return true;
}

std::string Evaluator::arrayName() const {
  const std::string& v = model_.jobList.variable;
  return v.substr(v.rfind('.') + 1);
}

std::string Evaluator::arrayType() const { return template_->module->types[arrayTypeId_].name; }

void Evaluator::writeJobs(const JobList& list, uint8_t* memory) const {
  const bc::Module& m = *template_->module;
  auto put = [&](const bc::VarRef& ref, int64_t v) { bc::writeValueFromText(m, ref, std::to_string(v), memory); };
  for (size_t i = 0; i < list.jobs.size(); ++i) {
    const Job& j = list.jobs[i];
    put(slots_[i].device, j.device);
    put(slots_[i].code, j.code);
    for (size_t w = 0; w < slots_[i].waits.size(); ++w) put(slots_[i].waits[w], w < j.waits.size() ? j.waits[w] : 0);
  }
  if (count_) put(*count_, static_cast<int64_t>(list.jobs.size()));
  for (const auto& [ref, value] : presets_) bc::writeValueFromText(m, ref, value, memory);
}

std::unique_ptr<cell::Cell> Evaluator::run(const JobList& list, Evaluation& out) const {
  out = {};
  if (list.jobs.size() > slots_.size()) {
    out.reason = "the job list has " + std::to_string(list.jobs.size()) + " jobs; '" + model_.jobList.variable + "' holds " +
                 std::to_string(slots_.size());
    return nullptr;
  }
  for (const Job& j : list.jobs)
    if (j.waits.size() > model_.jobList.waitFields.size()) {
      out.reason = "job " + model_.operations[j.operation].name + " must wait for " + std::to_string(j.waits.size()) +
                   " jobs; the job list has " + std::to_string(model_.jobList.waitFields.size()) + " wait fields";
      return nullptr;
    }
  std::string progress;
  auto cell = runInstance(*template_, template_->root, [&](uint8_t* memory) { writeJobs(list, memory); }, model_.timeLimitNs, out,
                          [&](const uint8_t* memory) {
                            if (progress_) progress = bc::formatValue(*template_->module, *progress_, memory);
                          });
  if (out.end == RunEnd::TimeLimit && progress_)
    out.reason += " (" + progress + " of " + std::to_string(list.jobs.size()) + " jobs finished)";
  return cell;
}

Evaluation Evaluator::evaluate(const JobList& list) const {
  Evaluation e;
  run(list, e);
  return e;
}

void parallelFor(size_t count, unsigned threads, const std::function<void(size_t)>& body) {
  std::atomic<size_t> next{0};
  auto work = [&] {
    for (size_t i; (i = next.fetch_add(1)) < count;) body(i);
  };
  threads = std::max(1u, std::min<unsigned>(threads, static_cast<unsigned>(std::max<size_t>(count, 1))));
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
}

std::vector<Evaluation> evaluateAll(const Evaluator& evaluator, const std::vector<JobList>& batch, unsigned threads) {
  std::vector<Evaluation> results(batch.size());
  parallelFor(batch.size(), threads, [&](size_t i) { results[i] = evaluator.evaluate(batch[i]); });
  return results;
}

}  // namespace virtcom::optimize

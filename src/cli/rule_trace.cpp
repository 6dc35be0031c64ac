#include "cli/rule_trace.hpp"

#include <algorithm>
#include <iostream>

#include "cli/common.hpp"
#include "core/ascii.hpp"
#include "core/diagnostics.hpp"
#include "lang/ad/lower.hpp"
#include "lang/ad/reader.hpp"
#include "lang/ad/rule_trace.hpp"
#include "lang/ad/tables.hpp"

namespace virtcom::cli {

namespace {

bool isDiagramFile(const std::string& path) { return ad::isDiagramPath(path) || ad::isXmlDiagramPath(path); }

// An instance of a diagram file's PROGRAM that a task runs (the PROGRAM itself without a
// CONFIGURATION; `name WITH task : Program` with one), and that task.
struct RunningInstance {
  std::string name;
  uint32_t task = 0;
};

// The first instance of `program` in task order; nullopt if no task runs it (a configuration
// that runs other programs).
std::optional<RunningInstance> runningInstance(const bc::Module& module, const std::string& program) {
  for (uint32_t t = 0; t < module.tasks.size(); ++t)
    for (uint32_t p : module.tasks[t].programs) {
      const bc::ProgramInstance& instance = module.programs.at(p);
      if (instance.pou < module.pous.size() && iequalsAscii(module.pous[instance.pou].name, program)) return RunningInstance{instance.name, t};
    }
  return std::nullopt;
}

// The fired flag of the k-th rule (from 1) of the instance, and its task.
std::optional<plc::CountedRule> firedFlag(const bc::Module& module, const RunningInstance& instance, size_t k) {
  auto flag = bc::resolveVariable(module, instance.name + "." + std::string(ad::kFiredVariable) + "[" + std::to_string(k) + "]");
  if (!flag) return std::nullopt;
  return plc::CountedRule{*flag, instance.task};
}

}  // namespace

std::optional<std::vector<WatchedRule>> findWatchedRules(const std::vector<std::string>& files, const bc::Module& module) {
  std::vector<WatchedRule> found;
  for (const std::string& path : files) {
    if (!isDiagramFile(path)) continue;
    std::optional<ad::Program> program = readDiagramFile(path);
    if (!program) return std::nullopt;
    std::optional<RunningInstance> instance = runningInstance(module, program->name);
    if (!instance) continue;  // a PROGRAM no task runs (a configuration that runs others)
    std::vector<ad::TracedRule> rules = ad::tracedRules(*program);
    for (size_t k = 0; k < rules.size(); ++k)
      if (auto flag = firedFlag(module, *instance, k + 1)) found.push_back({std::move(rules[k]), *flag});
  }
  return found;
}

std::optional<RuleTracer> RuleTracer::load(const std::vector<std::string>& files, const bc::Module& module) {
  if (!std::ranges::any_of(files, isDiagramFile)) {
    std::cerr << "error: --trace-rules: no activity-diagram file (.ad, .adxml) among the PLC sources\n";
    return std::nullopt;
  }
  auto rules = findWatchedRules(files, module);
  if (!rules) return std::nullopt;
  RuleTracer tracer;
  for (const WatchedRule& w : *rules)
    tracer.rules_.push_back({w.rule.diagram + " rule " + w.rule.index + " fired: " + w.rule.then, w.counted.flag});
  return tracer;
}

void RuleTracer::print(uint64_t scan, const uint8_t* memory, std::ostream& out) const {
  for (const Watched& rule : rules_)
    if (plc::flagSet(rule.flag, memory)) out << "scan " << scan << "  " << rule.prefix << '\n';
}

std::optional<RuleTables> RuleTables::load(const std::vector<std::string>& files, const bc::Module& module) {
  RuleTables tables;
  std::vector<plc::CountedRule> counted;
  for (const std::string& path : files) {
    if (!isDiagramFile(path)) continue;
    std::optional<ad::Program> program = readDiagramFile(path);
    if (!program) return std::nullopt;
    std::optional<RunningInstance> instance = runningInstance(module, program->name);
    size_t k = 0;  // fired flags run over the file's rules, diagram after diagram
    for (const ad::Diagram& d : program->diagrams) {
      ad::DiagramTables decomposed = ad::decompose(d);
      auto section = static_cast<uint32_t>(tables.sections_.size());
      tables.sections_.push_back({program->name, d.name, ad::luTable(decomposed), ad::ruleTable(decomposed), {}});
      tables.sections_.back().firings.resize(decomposed.rules.size());
      for (uint32_t row = 0; row < decomposed.rules.size(); ++row) {
        ++k;
        if (!instance) continue;  // never scanned: its rules keep their zero counts
        if (auto rule = firedFlag(module, *instance, k)) {
          counted.push_back(*rule);
          tables.rows_.push_back({section, row});
        }
      }
    }
  }
  tables.counter_ = plc::RuleCounter(std::move(counted), module.tasks.size());
  return tables;
}

std::vector<report::DiagramTablesSection> RuleTables::sections() const {
  std::vector<report::DiagramTablesSection> out = sections_;
  const std::vector<plc::RuleFiring>& firings = counter_.firings();
  for (size_t r = 0; r < rows_.size(); ++r)
    out[rows_[r].section].firings[rows_[r].row] = {firings[r].scans, firings[r].firstNs, firings[r].lastNs};
  return out;
}

}  // namespace virtcom::cli

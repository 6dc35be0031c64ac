#include "cli/rule_trace.hpp"

#include <algorithm>
#include <iostream>

#include "cli/common.hpp"
#include "core/diagnostics.hpp"
#include "lang/ad/lower.hpp"
#include "lang/ad/reader.hpp"

namespace virtcom::cli {

namespace {

bool isDiagramFile(const std::string& path) { return ad::isDiagramPath(path) || ad::isXmlDiagramPath(path); }

}  // namespace

std::optional<std::vector<WatchedRule>> findWatchedRules(const std::vector<std::string>& files, const bc::Module& module) {
  std::vector<WatchedRule> found;
  for (const std::string& path : files) {
    if (!isDiagramFile(path)) continue;
    auto text = readSources({path});
    if (!text) return std::nullopt;
    Diagnostics diags;  // the file compiled, so it reads cleanly
    ad::Program program = ad::readProgramFile(0, path, text->front().text, diags);
    std::vector<ad::TracedRule> rules = ad::tracedRules(program);
    for (size_t k = 0; k < rules.size(); ++k) {
      std::string flag = program.name + "." + std::string(ad::kFiredVariable) + "[" + std::to_string(k + 1) + "]";
      auto ref = bc::resolveVariable(module, flag);
      if (!ref) continue;  // a PROGRAM never instantiated (a configuration that runs others)
      found.push_back({std::move(rules[k]), *ref});
    }
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
    tracer.rules_.push_back({w.rule.diagram + " rule " + w.rule.index + " fired: " + w.rule.then, w.flag});
  return tracer;
}

void RuleTracer::print(uint64_t scan, const uint8_t* memory, std::ostream& out) const {
  for (const Watched& rule : rules_)
    if (rule.flag.bit < 0 ? memory[rule.flag.address] != 0 : (memory[rule.flag.address] >> rule.flag.bit) & 1) out << "scan " << scan << "  " << rule.prefix << '\n';
}

}  // namespace virtcom::cli

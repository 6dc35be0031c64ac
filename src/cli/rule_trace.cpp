#include "cli/rule_trace.hpp"

#include <iostream>

#include "cli/common.hpp"
#include "core/diagnostics.hpp"
#include "lang/ad/lower.hpp"
#include "lang/ad/reader.hpp"
#include "lang/ad/rule_trace.hpp"

namespace virtcom::cli {

std::optional<RuleTracer> RuleTracer::load(const std::vector<std::string>& files, const bc::Module& module) {
  RuleTracer tracer;
  bool anyDiagram = false;
  for (const std::string& path : files) {
    if (!ad::isDiagramPath(path) && !ad::isXmlDiagramPath(path)) continue;
    anyDiagram = true;
    auto text = readSources({path});
    if (!text) return std::nullopt;
    Diagnostics diags;  // the file compiled, so it reads cleanly
    ad::Program program = ad::readProgramFile(0, path, text->front().text, diags);
    std::vector<ad::TracedRule> rules = ad::tracedRules(program);
    for (size_t k = 0; k < rules.size(); ++k) {
      std::string flag = program.name + "." + std::string(ad::kFiredVariable) + "[" + std::to_string(k + 1) + "]";
      auto ref = bc::resolveVariable(module, flag);
      if (!ref) continue;  // a PROGRAM never instantiated (a configuration that runs others)
      tracer.rules_.push_back({rules[k].diagram + " rule " + rules[k].index + " fired: " + rules[k].then, *ref});
    }
  }
  if (anyDiagram) return tracer;
  std::cerr << "error: --trace-rules: no activity-diagram file (.ad, .adxml) among the PLC sources\n";
  return std::nullopt;
}

void RuleTracer::print(uint64_t scan, const uint8_t* memory, std::ostream& out) const {
  for (const Watched& rule : rules_)
    if (rule.flag.bit < 0 ? memory[rule.flag.address] != 0 : (memory[rule.flag.address] >> rule.flag.bit) & 1) out << "scan " << scan << "  " << rule.prefix << '\n';
}

}  // namespace virtcom::cli

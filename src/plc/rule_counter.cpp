#include "plc/rule_counter.hpp"

#include <algorithm>

namespace virtcom::plc {

RuleCounter::RuleCounter(std::vector<CountedRule> rules, size_t taskCount)
    : firings_(rules.size()), scansSeen_(taskCount, 0) {
  rules_.reserve(rules.size());
  for (const CountedRule& r : rules) rules_.push_back({r, false});
}

void RuleCounter::count(const Runtime& plc) {
  // The tick that just ran started at the time before the next one.
  const int64_t nowNs = plc.nextTickNs() - plc.baseTickNs();
  const uint8_t* memory = plc.machine().memory();
  for (size_t r = 0; r < rules_.size(); ++r) {
    Counted& rule = rules_[r];
    const uint64_t scans = plc.stats(rule.rule.task).scans - scansSeen_[rule.rule.task];
    if (scans == 0) continue;
    // All but the last of these scans were repeats passed over by event-driven time: the flag
    // stood as the last counted scan left it, until the tick before this one.
    RuleFiring& f = firings_[r];
    if (rule.lastSet && scans > 1) {
      f.scans += scans - 1;
      f.lastNs = nowNs - plc.baseTickNs();
    }
    rule.lastSet = flagSet(rule.rule.flag, memory);
    if (!rule.lastSet) continue;
    if (f.scans++ == 0) f.firstNs = nowNs;
    f.lastNs = nowNs;
  }
  for (uint32_t t = 0; t < scansSeen_.size(); ++t) scansSeen_[t] = plc.stats(t).scans;
}

void RuleCounter::restart() {
  std::ranges::fill(firings_, RuleFiring{});
  std::ranges::fill(scansSeen_, 0);
  for (Counted& r : rules_) r.lastSet = false;
}

}  // namespace virtcom::plc

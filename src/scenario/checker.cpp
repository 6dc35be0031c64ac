// Assertions judged tick by tick and at the end of the run.
#include "scenario/checker.hpp"

#include <sstream>

#include "scenario/bind.hpp"

namespace virtcom::scenario {

Checker::Checker(const Plan& plan, const cell::Cell& cell) : plan_(plan), cell_(cell), states_(plan.assertions.size()) {
  for (size_t i = 0; i < states_.size(); ++i) {
    const size_t n = plan.assertions[i].conditions.size();
    states_[i].was.assign(n, 0);
    states_[i].seenNs.assign(n, -1);
  }
}

ValueSources Checker::sources() const {
  return {plc_ ? plc_->machine().memory() : nullptr, &cell_.bus, &cell_.world};
}

std::string Checker::values(const Expression& e) const {
  std::string operands = e.describeOperands(sources());
  return operands.empty() ? std::string() : " (" + operands + ")";
}

void Checker::fail(State& s, int64_t nowNs, std::string message) {
  s.decided = s.failed = true;
  s.timeNs = nowNs;
  s.message = std::move(message);
}

void Checker::begin(const Trace&) {}

void Checker::tick(const Trace&, int64_t nowNs) {
  for (size_t i = 0; i < states_.size(); ++i)
    if (!states_[i].decided) judgeTick(plan_.assertions[i], states_[i], nowNs);
}

void Checker::judgeTick(const Assertion& a, State& s, int64_t nowNs) {
  using Kind = Assertion::Kind;
  const bool inWindow = nowNs >= a.fromNs && nowNs <= a.toNs;
  switch (a.kind) {
    case Kind::At:
      if (nowNs < a.atNs) return;
      s.decided = true;
      if (!a.conditions[0].holds(sources()))
        fail(s, nowNs, "'" + a.conditions[0].text() + "' is false" + values(a.conditions[0]));
      return;
    case Kind::Eventually:
      if (inWindow && a.conditions[0].holds(sources())) {
        s.decided = true;
        s.timeNs = nowNs;
      } else if (nowNs > a.toNs) {
        fail(s, nowNs, "'" + a.conditions[0].text() + "' did not become true by " + formatSeconds(a.toNs) + values(a.conditions[0]));
      }
      return;
    case Kind::Always:
    case Kind::Never: {
      if (!inWindow) return;
      const bool held = a.conditions[0].holds(sources());
      if (held == (a.kind == Kind::Never))
        fail(s, nowNs, "'" + a.conditions[0].text() + "' became " + (held ? "true" : "false") + values(a.conditions[0]));
      return;
    }
    case Kind::InOrder: judgeOrder(a, s, nowNs); return;
    case Kind::PlcRunning:
      if (inWindow && plc_ && plc_->state() != plc::PlcState::Run)
        fail(s, nowNs, std::string("the PLC is in ") + plc::stateName(plc_->state()));
      return;
    default: return;  // judged at the end
  }
}

// Each condition's first rise, in the listed order; several in the same tick count as in order.
void Checker::judgeOrder(const Assertion& a, State& s, int64_t nowNs) {
  const ValueSources in = sources();
  for (size_t k = 0; k < a.conditions.size(); ++k) {
    const bool now = a.conditions[k].holds(in);
    const bool rose = now && !s.was[k];
    s.was[k] = now;
    if (!rose || s.seenNs[k] >= 0) continue;
    s.seenNs[k] = nowNs;
    for (size_t before = 0; before < k; ++before)
      if (s.seenNs[before] < 0) {
        fail(s, nowNs, "'" + a.conditions[k].text() + "' became true before '" + a.conditions[before].text() + "'");
        return;
      }
  }
}

void Checker::end(const Trace& trace) {
  for (size_t i = 0; i < states_.size(); ++i)
    if (!states_[i].decided) judgeEnd(plan_.assertions[i], states_[i], trace);
}

void Checker::judgeEnd(const Assertion& a, State& s, const Trace& trace) {
  using Kind = Assertion::Kind;
  const int64_t endNs = trace.endNs;
  s.decided = true;
  switch (a.kind) {
    case Kind::At: fail(s, endNs, "the run ended (" + trace.endMessage + ") before " + formatSeconds(a.atNs)); return;
    case Kind::Eventually:
      fail(s, endNs, "'" + a.conditions[0].text() + "' never became true; the run ended (" + trace.endMessage + ")" + values(a.conditions[0]));
      return;
    case Kind::InOrder:
      for (size_t k = 0; k < a.conditions.size(); ++k)
        if (s.seenNs[k] < 0) {
          fail(s, endNs, "'" + a.conditions[k].text() + "' never became true" + values(a.conditions[k]));
          return;
        }
      return;
    case Kind::CycleTime:
      if (trace.cyclesCompleted == 0) fail(s, endNs, "no cycle completed; the run ended (" + trace.endMessage + ")");
      else if (static_cast<double>(trace.cycles.maxNs()) > a.max)
        fail(s, endNs, "cycle time " + formatSeconds(trace.cycles.maxNs()) + " > " + formatSeconds(static_cast<int64_t>(a.max)));
      else if (static_cast<double>(trace.cycles.minNs()) < a.min)
        fail(s, endNs, "cycle time " + formatSeconds(trace.cycles.minNs()) + " < " + formatSeconds(static_cast<int64_t>(a.min)));
      return;
    case Kind::Energy: {
      double joules = 0;
      for (size_t d = 0; d < trace.totals.size(); ++d)
        if (a.device < 0 || static_cast<size_t>(a.device) == d) joules += trace.totals[d].energyJ;
      std::ostringstream text;
      text << "energy " << joules << " J";
      if (joules > a.max) fail(s, endNs, text.str() + " > " + std::to_string(a.max) + " J");
      else if (joules < a.min) fail(s, endNs, text.str() + " < " + std::to_string(a.min) + " J");
      return;
    }
    case Kind::NoCollision:
      if (!trace.collisions.empty()) {
        const CollisionRecord& c = trace.collisions.front();
        fail(s, c.timeNs, trace.devices[c.deviceA].name + " and " + trace.devices[c.deviceB].name + " collided in " + trace.labels[c.zone]);
      }
      return;
    case Kind::Final:
      if (!a.conditions[0].holds(sources()))
        fail(s, endNs, "'" + a.conditions[0].text() + "' is false at the end" + values(a.conditions[0]));
      return;
    case Kind::RunEnd:
      if (static_cast<int>(trace.end) != a.runEnd)
        fail(s, endNs, std::string("the run ended: ") + runEndName(trace.end) + " (" + trace.endMessage + ")");
      return;
    default: return;  // Always, Never, PlcRunning: nothing broke them
  }
}

std::vector<Failure> Checker::failures() const {
  std::vector<Failure> out;
  for (size_t i = 0; i < states_.size(); ++i)
    if (states_[i].failed) out.push_back({i, plan_.assertions[i].loc, states_[i].timeNs, states_[i].message});
  return out;
}

}  // namespace virtcom::scenario

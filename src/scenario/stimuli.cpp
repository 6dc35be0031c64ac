// Steps of a scenario, applied between scans.
#include "scenario/stimuli.hpp"

#include <algorithm>
#include <cstring>

#include "plc/retain_file.hpp"
#include "plc/variable_text.hpp"

namespace virtcom::scenario {

bool writeBytes(const bc::VarRef& ref, std::span<const uint8_t> bytes, plc::Runtime& plc) {
  uint8_t* at = plc.machine().memory() + ref.address;
  bool changed = false;
  if (ref.bit >= 0) {
    const uint8_t mask = static_cast<uint8_t>(1u << ref.bit);
    const uint8_t next = static_cast<uint8_t>((*at & ~mask) | (bytes[0] & mask));
    changed = next != *at;
    *at = next;
  } else {
    changed = std::memcmp(at, bytes.data(), bytes.size()) != 0;
    std::memcpy(at, bytes.data(), bytes.size());
  }
  plc::syncInputImage(plc.module(), ref, plc.machine().memory(), plc.inputImage());
  if (changed) plc.inputsTouched();
  return changed;
}

bool writeValue(const Action& a, plc::Runtime& plc) { return writeBytes(a.ref, a.bytes, plc); }

namespace {

size_t countActions(const Plan& plan, Action::Kind kind) {
  size_t n = 0;
  for (const Step& s : plan.steps)
    n += static_cast<size_t>(std::ranges::count_if(s.actions, [kind](const Action& a) { return a.kind == kind; }));
  return n;
}

constexpr uint8_t kFalse[1] = {0};  // a released button's BOOL, bit or byte

}  // namespace

Stimuli::Stimuli(const Plan& plan, cell::Cell& cell) : plan_(plan), cell_(cell), stepDone_(plan.steps.size(), 0) {
  forces_.reserve(countActions(plan, Action::Kind::Force));
  held_.reserve(countActions(plan, Action::Kind::Press));
  if (!cell.module) return;
  uint32_t total = 0;
  for (const plc::RetainedVariable& v : plc::retainedVariables(*cell.module)) {
    const uint32_t size = cell.module->types[v.type].size;
    retained_.push_back({v.address, size});
    total += size;
  }
  retainedBytes_.resize(total);
}

void Stimuli::preset(plc::Runtime& plc) {
  for (const Action& a : plan_.presets) writeValue(a, plc);
}

void Stimuli::beforeScan(plc::Runtime& plc) {
  const int64_t nowNs = plc.nextTickNs();
  if (restartAtNs_ >= 0 && nowNs >= restartAtNs_) restart(plc);
  std::erase_if(held_, [&](const Held& h) {  // buttons whose press is over go back to FALSE
    if (nowNs < h.releaseAtNs) return false;
    writeBytes(h.press->ref, kFalse, plc);
    return true;
  });
  ValueSources in{plc.machine().memory(), &cell_.bus, &cell_.world};
  for (size_t i = 0; i < plan_.steps.size(); ++i) {
    const Step& s = plan_.steps[i];
    if (stepDone_[i]) continue;
    const bool due = s.atNs >= 0 ? nowNs >= s.atNs : s.when.holds(in);
    if (!due) continue;
    stepDone_[i] = 1;
    for (const Action& a : s.actions) apply(a, plc, nowNs);
  }
  if (restartAtNs_ < 0)
    for (const Action* f : forces_) writeValue(*f, plc);
}

void Stimuli::apply(const Action& a, plc::Runtime& plc, int64_t nowNs) {
  switch (a.kind) {
    case Action::Kind::Set: writeValue(a, plc); break;
    case Action::Kind::Force:
      std::erase_if(forces_, [&](const Action* f) { return f->ref.address == a.ref.address && f->ref.bit == a.ref.bit; });
      forces_.push_back(&a);  // within the capacity reserved for every force
      writeValue(a, plc);
      break;
    case Action::Kind::Release:
      std::erase_if(forces_, [&](const Action* f) { return f->ref.address == a.ref.address && f->ref.bit == a.ref.bit; });
      break;
    case Action::Kind::ReleaseAll: forces_.clear(); break;
    case Action::Kind::Press:
      std::erase_if(held_, [&](const Held& h) { return h.press->ref.address == a.ref.address && h.press->ref.bit == a.ref.bit; });
      held_.push_back({&a, nowNs + a.durationNs});  // within the capacity reserved for every press
      writeValue(a, plc);
      break;
    case Action::Kind::Fact: cell_.world.setFact(a.index, a.factValue); break;
    case Action::Kind::Fault: cell_.devices[a.index]->faults() = a.plan; break;
    case Action::Kind::Parameter: cell_.devices[a.index]->swapParameters(*a.edited); break;
    case Action::Kind::PowerLoss:
      if (restartAtNs_ < 0) powerDown(plc);
      restartAtNs_ = nowNs + a.durationNs;
      break;
  }
}

void Stimuli::powerDown(plc::Runtime& plc) {
  uint8_t* memory = plc.machine().memory();
  size_t at = 0;
  for (const Retained& r : retained_) {
    std::memcpy(retainedBytes_.data() + at, memory + r.address, r.size);
    at += r.size;
  }
  plc.machine().coldStart();  // the outputs de-energised: every variable back at its initial value
  plc.stop();
  plc.inputsTouched();
}

void Stimuli::restart(plc::Runtime& plc) {
  restartAtNs_ = -1;
  uint8_t* memory = plc.machine().memory();
  plc.machine().coldStart();
  size_t at = 0;
  for (const Retained& r : retained_) {
    std::memcpy(memory + r.address, retainedBytes_.data() + at, r.size);
    at += r.size;
  }
  plc.start();
  plc.inputsTouched();
}

}  // namespace virtcom::scenario

// Binding a scenario's sections to its loaded cell: names to addresses, values to bytes, texts to
// conditions, all before the run, so applying and judging them later costs no lookup.
#include "scenario/bind.hpp"

#include <algorithm>
#include <cstdio>

#include "core/cell_diagnostic_codes.hpp"
#include "core/trace.hpp"
#include "plant/config_helpers.hpp"
#include "plc/variable_text.hpp"
#include "scenario/parameter_change.hpp"

namespace virtcom::scenario {

std::string formatSeconds(int64_t ns) {
  char text[48];
  std::snprintf(text, sizeof text, "%.9f", static_cast<double>(ns) * 1e-9);
  std::string s = text;
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  return s + " s";
}

namespace {

struct RunEndWord {
  std::string_view word;
  RunEnd end;
};
// `run_end:` values: runEndName()'s texts have spaces; these are YAML words.
constexpr RunEndWord kRunEnds[] = {{"completed", RunEnd::Completed},      {"time_limit", RunEnd::TimeLimit},
                                   {"plc_fault", RunEnd::PlcFault},       {"device_error", RunEnd::DeviceError},
                                   {"collision", RunEnd::Collision}};

class Binder {
 public:
  Binder(ConfigReader& top, cell::Cell& cell, Controlled controlled)
      : top_(top), cell_(cell), controlled_(controlled), diags_(top.diags()) {
    scope_ = {cell.module.get(), &cell.bus, &cell.world};
  }

  Plan bind() {
    readRunSettings();
    if (const ConfigNode* sets = top_.child("set")) readAssignments(*sets, Action::Kind::Set, plan_.presets);
    if (!refusedWithoutCell(top_, "faults"))
      if (const ConfigNode* faults = top_.child("faults")) readLoadFaults(*faults);
    if (const ConfigNode* steps = top_.child("steps")) forEachItem(*steps, "steps", [&](const ConfigNode& n) { readStep(n); });
    if (const ConfigNode* expect = top_.child("expect")) forEachItem(*expect, "expect", [&](const ConfigNode& n) { readAssertion(n); });
    plan_.xfail = top_.optString("xfail", "");
    top_.rejectUnknownKeys();
    return std::move(plan_);
  }

 private:
  template <class Fn>
  void forEachItem(const ConfigNode& list, const char* key, Fn fn) {
    if (list.kind() != ConfigNode::Kind::List) {
      diags_.error(celldiag::C060, list.loc(), std::string("'") + key + "' must be a list (docs/scenarios.md)");
      return;
    }
    for (const ConfigNode& item : list.items()) fn(item);
  }

  void readRunSettings() {
    cell::RunSettings& run = cell_.run;
    run.timeLimitNs = plant::optDurationNs(top_, "time_limit", run.timeLimitNs);
    if (!refusedWithoutCell(top_, "cycles")) run.cycles = static_cast<uint32_t>(top_.optInt("cycles", run.cycles));
    if (!refusedWithoutCell(top_, "stop_on_device_error"))
      run.stopOnDeviceError = top_.optBool("stop_on_device_error", run.stopOnDeviceError);
    if (!refusedWithoutCell(top_, "stop_on_collision")) run.stopOnCollision = top_.optBool("stop_on_collision", run.stopOnCollision);
  }

  // In a scenario of a PLC program alone, a key about devices, their world or the cell's cycle is
  // a mistake, said so at the key (rather than "no device named ..." or an assertion that holds
  // vacuously).
  bool refusedWithoutCell(ConfigReader& r, const char* key) {
    if (controlled_ != Controlled::ProgramAlone || !r.has(key)) return false;
    r.child(key);
    r.error(r.node().keyLoc(key), std::string("'") + key +
                                      "' needs a cell (devices, their world, its cycle): this scenario runs a PLC program alone "
                                      "('program:')");
    return true;
  }

  Expression condition(const ConfigNode& node) {
    if (node.kind() != ConfigNode::Kind::Scalar) {
      diags_.error(celldiag::C061, node.loc(), "a condition is one line of text, e.g. \"MAIN.x >= 3 AND NOT Robot1.busy\"");
      return {};
    }
    if (scope_.module) plan_.usesPlc = true;
    return Expression::parse(node.scalar(), node.loc(), scope_, diags_);
  }

  // `{VARIABLE: VALUE, ...}` (set, force) into one action each.
  void readAssignments(const ConfigNode& map, Action::Kind kind, std::vector<Action>& out) {
    if (map.kind() != ConfigNode::Kind::Map) {
      diags_.error(celldiag::C060, map.loc(), "expected a map of PLC variables to values, e.g. {MAIN.start: TRUE}");
      return;
    }
    for (const auto& [name, value] : map.entries()) {
      Action a;
      a.kind = kind;
      a.name = name;
      if (!resolveVariable(name, map.keyLoc(name), a.ref)) continue;
      const bc::TypeDesc& type = cell_.module->types[a.ref.type];
      std::vector<uint8_t> scratch(cell_.module->memorySize(), 0);
      std::string problem = plc::writeVariableText(*cell_.module, a.ref, value.scalar(), scratch.data(), nullptr);
      if (!problem.empty()) {
        diags_.error(celldiag::C060, value.loc(), "'" + name + "': " + problem);
        continue;
      }
      const size_t size = a.ref.bit >= 0 ? 1 : type.size;
      a.bytes.assign(scratch.begin() + a.ref.address, scratch.begin() + a.ref.address + size);
      out.push_back(std::move(a));
    }
  }

  bool resolveVariable(const std::string& name, SourceLocation loc, bc::VarRef& ref) {
    if (!cell_.module) {
      diags_.error(celldiag::C060, loc, "'" + name + "': the cell has no soft PLC to write");
      return false;
    }
    plan_.usesPlc = true;
    auto found = bc::resolveVariable(*cell_.module, name);
    if (!found) {
      diags_.error(celldiag::C060, loc, "the PLC has no variable '" + name + "' (use the qualified name, e.g. MAIN.start)");
      return false;
    }
    if (found->readOnly) {
      diags_.error(celldiag::C060, loc, "'" + name + "' is a CONSTANT and cannot be written");
      return false;
    }
    ref = *found;
    return true;
  }

  int deviceIndex(ConfigReader& r) {
    const std::string name = r.requireString("device");
    for (size_t i = 0; i < cell_.devices.size(); ++i)
      if (cell_.devices[i]->name() == name) return static_cast<int>(i);
    if (!name.empty()) {
      std::string names;
      for (const auto& d : cell_.devices) names += (names.empty() ? "" : ", ") + d->name();
      r.error(r.node().find("device")->loc(), "no device named '" + name + "' (the cell has: " + names + ")");
    }
    return -1;
  }

  // `faults:` entries: a device's plan for the whole run, as the cell file's `faults:` keys.
  void readLoadFaults(const ConfigNode& list) {
    forEachItem(list, "faults", [&](const ConfigNode& item) {
      ConfigReader r(item, diags_, "fault");
      if (r.has("link")) return readLinkLoss(r);
      int device = deviceIndex(r);
      if (device >= 0) cell::readDeviceFaults(*cell_.devices[static_cast<size_t>(device)], r);
    });
  }

  // `{link: plc, comm_loss: [{at: T, duration: D}, ...]}`: the external PLC's link cut.
  void readLinkLoss(ConfigReader& r) {
    const ConfigNode& node = r.node();
    if (r.requireString("link") != "plc")
      diags_.error(celldiag::C063, node.find("link")->loc(), "'link' names the link to the cell's external PLC: 'plc'");
    if (!cell_.externalPlc())
      diags_.error(celldiag::C063, node.keyLoc("link"),
                   "the cell's controller is its soft PLC: only an external PLC ('plc: ads:', 'plc: modbus:' or 'plc: opcua:') has a "
                   "link to lose");
    const ConfigNode* losses = r.child("comm_loss");
    if (!losses || losses->kind() != ConfigNode::Kind::List || losses->items().empty())
      diags_.error(celldiag::C063, losses ? losses->loc() : node.loc(), "'comm_loss' lists windows, e.g. [{at: 2 s, duration: 1 s}]");
    else
      for (const ConfigNode& w : losses->items()) {
        ConfigReader wr(w, diags_, "'comm_loss' window");
        plan_.linkLosses.push_back({plant::requireDurationNs(wr, "at"), plant::requireDurationNs(wr, "duration")});
        wr.rejectUnknownKeys();
      }
    r.rejectUnknownKeys();
  }

  void readStep(const ConfigNode& node) {
    ConfigReader r(node, diags_, "step");
    Step step;
    step.loc = node.loc();
    const ConfigNode* when = r.child("when");
    if (when) step.when = condition(*when);
    if (r.has("at") == (when != nullptr)) r.error(node.loc(), "a step has either 'at: TIME' or 'when: CONDITION'");
    step.atNs = when ? -1 : plant::optDurationNs(r, "at", 0);
    if (const ConfigNode* sets = r.child("set")) readAssignments(*sets, Action::Kind::Set, step.actions);
    if (const ConfigNode* forces = r.child("force")) readAssignments(*forces, Action::Kind::Force, step.actions);
    if (const ConfigNode* presses = r.child("press")) readPresses(*presses, step.actions);
    if (const ConfigNode* release = r.child("release")) readRelease(*release, step.actions);
    if (const ConfigNode* facts = r.child("facts"); facts && !refusedWithoutCell(r, "facts")) readFacts(*facts, step.actions);
    if (const ConfigNode* fault = r.child("fault"); fault && !refusedWithoutCell(r, "fault")) readStepFault(*fault, step.actions);
    if (const ConfigNode* parameters = r.child("parameter"); parameters && !refusedWithoutCell(r, "parameter"))
      readParameters(*parameters, step.actions);
    if (r.has("power_loss")) {
      Action a;
      a.kind = Action::Kind::PowerLoss;
      a.durationNs = plant::requireDurationNs(r, "power_loss");
      if (!cell_.module) r.error(node.keyLoc("power_loss"), "'power_loss' needs the soft PLC");
      step.actions.push_back(std::move(a));
    }
    if (step.actions.empty() && r.ok())
      r.error(node.loc(), "a step does something: set, force, press, release, facts, fault, parameter or power_loss");
    r.rejectUnknownKeys();
    plan_.steps.push_back(std::move(step));
  }

  // `press: {VAR: DURATION, ...}`: an operator's push button, a BOOL TRUE from the step for
  // DURATION, then FALSE.
  void readPresses(const ConfigNode& map, std::vector<Action>& out) {
    if (map.kind() != ConfigNode::Kind::Map) {
      diags_.error(celldiag::C060, map.loc(), "'press' maps BOOL variables to how long they are pressed, e.g. {MAIN.startButton: 200 ms}");
      return;
    }
    ConfigReader r(map, diags_, "'press'");
    for (const auto& [name, value] : map.entries()) {
      Action a;
      a.kind = Action::Kind::Press;
      a.name = name;
      a.durationNs = plant::requireDurationNs(r, name);
      if (!resolveVariable(name, map.keyLoc(name), a.ref)) continue;
      const bc::TypeDesc& type = cell_.module->types[a.ref.type];
      if (type.kind != bc::TypeKind::Elementary || type.elem != ElemType::Bool) {
        diags_.error(celldiag::C060, map.keyLoc(name), "'" + name + "' is " + type.name + ": a pressed button is a BOOL");
        continue;
      }
      a.bytes = {static_cast<uint8_t>(a.ref.bit >= 0 ? 1u << a.ref.bit : 1u)};
      out.push_back(std::move(a));
    }
  }

  void readRelease(const ConfigNode& node, std::vector<Action>& out) {
    auto one = [&](const ConfigNode& n) {
      Action a;
      a.name = n.scalar();
      if (a.name == "all") a.kind = Action::Kind::ReleaseAll;
      else if (a.kind = Action::Kind::Release; !resolveVariable(a.name, n.loc(), a.ref)) return;
      out.push_back(std::move(a));
    };
    if (node.kind() == ConfigNode::Kind::List)
      for (const ConfigNode& n : node.items()) one(n);
    else one(node);
  }

  void readFacts(const ConfigNode& map, std::vector<Action>& out) {
    if (map.kind() != ConfigNode::Kind::Map) {
      diags_.error(celldiag::C060, map.loc(), "'facts' maps world facts to true or false, e.g. {stud1: false}");
      return;
    }
    ConfigReader r(map, diags_, "'facts'");
    for (const auto& [name, value] : map.entries()) {
      Action a;
      a.kind = Action::Kind::Fact;
      a.name = name;
      a.factValue = r.optBool(name, false);
      a.index = cell_.world.fact(name);  // a fact nothing else names yet is still a fact
      out.push_back(std::move(a));
    }
  }

  void readStepFault(const ConfigNode& node, std::vector<Action>& out) {
    ConfigReader r(node, diags_, "'fault'");
    Action a;
    a.kind = Action::Kind::Fault;
    int device = deviceIndex(r);
    a.plan = cell::readFaultPlan(r, 0);  // from this step on, every command fails unless at_command says which
    r.rejectUnknownKeys();
    if (device < 0) return;
    a.index = static_cast<uint32_t>(device);
    a.name = cell_.devices[a.index]->name();
    out.push_back(std::move(a));
  }

  // `{DEVICE.key: VALUE, ...}`: device parameters changed when the step acts.
  void readParameters(const ConfigNode& map, std::vector<Action>& out) {
    if (map.kind() != ConfigNode::Kind::Map) {
      diags_.error(celldiag::C062, map.loc(), "'parameter' maps device parameters to values, e.g. {Robot1.max_speed: 800 mm/s}");
      return;
    }
    for (const auto& [name, value] : map.entries()) {
      Action a;
      a.kind = Action::Kind::Parameter;
      a.name = name;
      a.edited = parameters_.edit(name, map.keyLoc(name), value, diags_, a.index);
      if (a.edited) out.push_back(std::move(a));
    }
  }

  // One entry of `expect:`: its kind is the first key of the table below that it has.
  void readAssertion(const ConfigNode& node) {
    ConfigReader r(node, diags_, "assertion");
    Assertion a;
    a.loc = node.loc();
    if (node.kind() == ConfigNode::Kind::Map && !node.entries().empty()) a.what = describe(node);
    a.fromNs = plant::optDurationNs(r, "from", 0);
    a.toNs = plant::optDurationNs(r, "to", INT64_MAX);
    if (const ConfigNode* c = r.child("that")) {
      a.kind = Assertion::Kind::At;
      a.atNs = plant::requireDurationNs(r, "at");
      a.conditions.push_back(condition(*c));
    } else if (const ConfigNode* e = r.child("eventually")) {
      a.kind = Assertion::Kind::Eventually;
      a.toNs = r.has("within") ? a.fromNs + plant::requireDurationNs(r, "within") : INT64_MAX;
      a.conditions.push_back(condition(*e));
    } else if (const ConfigNode* al = r.child("always")) {
      a.kind = Assertion::Kind::Always;
      a.conditions.push_back(condition(*al));
    } else if (const ConfigNode* nv = r.child("never")) {
      a.kind = Assertion::Kind::Never;
      a.conditions.push_back(condition(*nv));
    } else if (const ConfigNode* order = r.child("in_order")) {
      a.kind = Assertion::Kind::InOrder;
      if (order->kind() != ConfigNode::Kind::List || order->items().size() < 2)
        r.error(order->loc(), "'in_order' lists at least two conditions, e.g. [Robot1.busy, Press.busy]");
      else
        for (const ConfigNode& c : order->items()) a.conditions.push_back(condition(c));
    } else if (refusedWithoutCell(r, "cycle_time") || refusedWithoutCell(r, "energy") || refusedWithoutCell(r, "no_collision")) {
      return;
    } else if (const ConfigNode* cycle = r.child("cycle_time")) {
      a.kind = Assertion::Kind::CycleTime;
      readBounds(*cycle, Dimension::Time, 1e9, a);
    } else if (const ConfigNode* energy = r.child("energy")) {
      a.kind = Assertion::Kind::Energy;
      readBounds(*energy, Dimension::Energy, 1, a);
    } else if (r.child("no_collision")) {
      a.kind = Assertion::Kind::NoCollision;
    } else if (r.child("plc_running")) {
      a.kind = Assertion::Kind::PlcRunning;
      if (!cell_.module) r.error(node.loc(), "'plc_running' needs the soft PLC");
    } else if (const ConfigNode* code = r.child("fault_code")) {
      a.kind = Assertion::Kind::Eventually;
      a.toNs = r.has("within") ? a.fromNs + plant::requireDurationNs(r, "within") : INT64_MAX;
      ConfigReader f(*code, diags_, "'fault_code'");
      const std::string variable = f.requireString("variable");
      const int64_t value = f.requireInt("code");
      f.rejectUnknownKeys();
      if (f.ok()) a.conditions.push_back(Expression::parse(variable + " = " + std::to_string(value), code->find("variable")->loc(), scope_, diags_));
    } else if (const ConfigNode* fin = r.child("final")) {
      a.kind = Assertion::Kind::Final;
      a.conditions.push_back(condition(*fin));
    } else if (const ConfigNode* end = r.child("run_end")) {
      a.kind = Assertion::Kind::RunEnd;
      auto found = std::ranges::find_if(kRunEnds, [&](const RunEndWord& e) { return end->scalar() == e.word; });
      if (found == std::end(kRunEnds))
        r.error(end->loc(), "'" + end->scalar() + "' is not how a run ends (expected completed, time_limit, plc_fault, device_error or collision)");
      else a.runEnd = static_cast<int>(found->end);
    } else {
      r.error(node.loc(), "an assertion is one of: at + that, eventually, always, never, in_order, cycle_time, energy, "
                          "no_collision, plc_running, fault_code, final, run_end (docs/scenarios.md)");
      return;
    }
    r.rejectUnknownKeys();
    plan_.assertions.push_back(std::move(a));
  }

  // `{min: .., max: .., device: ..}` of cycle_time and energy, in SI times `scale`.
  void readBounds(const ConfigNode& node, Dimension dim, double scale, Assertion& a) {
    ConfigReader b(node, diags_, "bounds");
    if (a.kind == Assertion::Kind::Energy && b.has("device")) a.device = deviceIndex(b);
    if (b.has("min")) a.min = b.requireQuantity("min", dim) * scale;
    if (b.has("max")) a.max = b.requireQuantity("max", dim) * scale;
    if (!b.has("min") && !b.has("max")) b.error(node.loc(), "give 'min', 'max' or both, e.g. {max: 101 s}");
    b.rejectUnknownKeys();
  }

  // "eventually MAIN.cycleDone within 120 s": the entry's keys and scalars, in file order.
  static std::string describe(const ConfigNode& node) {
    std::string text;
    for (const auto& [key, value] : node.entries()) {
      text += (text.empty() ? "" : " ") + key;
      if (value.kind() == ConfigNode::Kind::Scalar) text += " " + value.scalar();
      else if (value.kind() == ConfigNode::Kind::Map)
        for (const auto& [k, v] : value.entries()) text += " " + k + " " + v.scalar();
      else
        for (const ConfigNode& item : value.items()) text += " [" + item.scalar() + "]";
    }
    return text;
  }

  ConfigReader& top_;
  cell::Cell& cell_;
  Controlled controlled_;
  Diagnostics& diags_;
  NameScope scope_;
  Plan plan_;
  ParameterEditor parameters_{cell_};
};

}  // namespace

Plan bindScenario(ConfigReader& top, cell::Cell& cell, Controlled controlled) { return Binder(top, cell, controlled).bind(); }

}  // namespace virtcom::scenario

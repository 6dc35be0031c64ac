// Reading the process model file (docs/optimise.md) and checking candidates against it.
#include "optimize/process_model.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "cell/yaml_config.hpp"
#include "core/cell_diagnostic_codes.hpp"
#include "core/config_node.hpp"

namespace virtcom::optimize {

const char* objectiveName(Objective o) {
  switch (o) {
    case Objective::Time: return "time";
    case Objective::Energy: return "energy";
    case Objective::Both: return "both";
  }
  return "time";
}

int ProcessModel::operationIndex(const std::string& name) const {
  for (size_t i = 0; i < operations.size(); ++i)
    if (operations[i].name == name) return static_cast<int>(i);
  return -1;
}

namespace {

using Kind = ConfigNode::Kind;

class ModelReader {
 public:
  ModelReader(ProcessModel& m, Diagnostics& diags) : m_(m), diags_(diags) {}

  void read(const ConfigNode& root) {
    ConfigReader top(root, diags_, "the process model");
    std::string cell = top.requireString("cell");
    if (!cell.empty()) m_.cellFile = (m_.file.parent_path() / cell).lexically_normal().string();
    readJobList(top);
    readDevices(top);
    std::string objective = top.optString("objective", "time");
    if (objective == "energy") m_.objective = Objective::Energy;
    else if (objective == "both") m_.objective = Objective::Both;
    else if (objective != "time") error(root.find("objective")->loc(), "'objective' is '" + objective + "', expected time, energy or both");
    if (top.has("time_limit")) {
      m_.timeLimitNs = static_cast<int64_t>(top.optQuantity("time_limit", Dimension::Time, 0) * 1e9 + 0.5);
      if (m_.timeLimitNs <= 0) error(root.find("time_limit")->loc(), "'time_limit' must be positive (e.g. 300 s)");
    }
    readOperations(top);
    readResources(top);
    computePrecedence();
    readSequences(top);
    top.rejectUnknownKeys();
  }

 private:
  void error(SourceLocation loc, std::string message) { diags_.error(celldiag::C070, loc, std::move(message)); }

  void readJobList(ConfigReader& top) {
    const ConfigNode* n = top.child("job_list");
    if (!n || n->kind() != Kind::Map) {
      error(n ? n->loc() : top.node().loc(), "the process model needs 'job_list:', the PLC's job-list variable and its fields");
      return;
    }
    ConfigReader r(*n, diags_, "'job_list'");
    JobListBinding& b = m_.jobList;
    b.loc = n->loc();
    b.variable = r.requireString("variable");
    if (const ConfigNode* f = r.child("fields")) {
      ConfigReader fields(*f, diags_, "'fields'");
      b.deviceField = fields.optString("device", b.deviceField);
      b.codeField = fields.optString("code", b.codeField);
      if (const ConfigNode* w = fields.child("waits")) {
        if (w->kind() != Kind::List) error(w->loc(), "'waits' must be a list of field names, e.g. [after1, after2, after3]");
        else
          for (const ConfigNode& item : w->items()) b.waitFields.push_back(item.scalar());
      }
      fields.rejectUnknownKeys();
    }
    b.count = r.optString("count", "");
    b.progress = r.optString("progress", "");
    if (const ConfigNode* s = r.child("set")) {
      if (s->kind() != Kind::Map) error(s->loc(), "'set' must map PLC variables to values, e.g. { MAIN.sequence: 0 }");
      else
        for (const auto& [name, value] : s->entries()) b.presets.emplace_back(name, value.scalar());
    }
    r.rejectUnknownKeys();
  }

  void readDevices(ConfigReader& top) {
    const ConfigNode* n = top.child("device_numbers");
    if (!n || n->kind() != Kind::Map || n->entries().empty()) {
      error(n ? n->loc() : top.node().loc(), "the process model needs 'device_numbers:', each device's number in the job list, e.g. { Robot1: 1 }");
      return;
    }
    ConfigReader r(*n, diags_, "'device_numbers'");
    for (const auto& [name, value] : n->entries()) m_.devices.emplace_back(name, r.requireInt(name));
  }

  // `device` + `code`, or a list of `alternatives` of them.
  Alternative readAlternative(const ConfigNode& node, ConfigReader& r) {
    Alternative a;
    a.deviceName = r.requireString("device");
    a.code = r.requireInt("code");
    auto it = std::ranges::find_if(m_.devices, [&](const auto& d) { return d.first == a.deviceName; });
    if (it != m_.devices.end()) a.device = it->second;
    else if (!a.deviceName.empty())
      error(node.find("device")->loc(), "no device '" + a.deviceName + "' in the model's 'device_numbers' (expected one of: " + deviceNames() + ")");
    a.name = r.optString("name", a.deviceName + ":" + std::to_string(a.code));
    return a;
  }

  std::string deviceNames() const {
    std::string s;
    for (const auto& [name, number] : m_.devices) s += (s.empty() ? "" : ", ") + name;
    return s;
  }

  void readOperations(ConfigReader& top) {
    const ConfigNode* n = top.child("operations");
    if (!n || n->kind() != Kind::List || n->items().empty()) {
      error(n ? n->loc() : top.node().loc(), "the process model needs 'operations:', a list of { name, device, code, after }");
      return;
    }
    for (const ConfigNode& item : n->items()) {
      ConfigReader r(item, diags_, "operation");
      Operation op;
      op.loc = item.loc();
      op.name = r.requireString("name");
      if (!op.name.empty() && m_.operationIndex(op.name) >= 0) error(item.find("name")->loc(), "operation '" + op.name + "' is defined twice");
      op.optional = r.optBool("optional", false);
      if (const ConfigNode* alts = r.child("alternatives")) {
        if (alts->kind() != Kind::List || alts->items().empty()) error(alts->loc(), "'alternatives' must be a list of { device, code }");
        else
          for (const ConfigNode& a : alts->items()) {
            ConfigReader ar(a, diags_, "alternative");
            op.alternatives.push_back(readAlternative(a, ar));
            ar.rejectUnknownKeys();
          }
      } else if (r.has("device") || r.has("code")) {
        op.alternatives.push_back(readAlternative(item, r));
      } else {
        error(item.loc(), "operation '" + op.name + "' needs 'device' and 'code', or 'alternatives'");
      }
      afterNames_.push_back(r.child("after"));
      m_.operations.push_back(std::move(op));
      r.rejectUnknownKeys();
    }
  }

  // The operation named by `node`, or -1 (reported).
  int operationAt(const ConfigNode& node, const std::string& where) {
    int i = m_.operationIndex(node.scalar());
    if (i < 0) error(node.loc(), where + " names '" + node.scalar() + "', which is no operation of the model");
    return i;
  }

  void readResources(ConfigReader& top) {
    const ConfigNode* n = top.child("resources");
    if (!n) return;
    if (n->kind() != Kind::Map) {
      error(n->loc(), "'resources' must map each resource to the operations using it, e.g. { SharedTable: [PlacePin, Screw] }");
      return;
    }
    for (const auto& [name, users] : n->entries()) {
      Resource res{name, {}};
      if (users.kind() != Kind::List) error(users.loc(), "resource '" + name + "' must list the operations using it");
      else
        for (const ConfigNode& u : users.items())
          if (int i = operationAt(u, "resource '" + name + "'"); i >= 0) res.users.push_back(static_cast<uint32_t>(i));
      m_.resources.push_back(std::move(res));
    }
  }

  // Resolves `after:` and closes it transitively; a cycle is reported at one of its operations.
  void computePrecedence() {
    const size_t n = m_.operations.size();
    for (size_t i = 0; i < n; ++i) {
      const ConfigNode* after = afterNames_[i];
      if (!after) continue;
      if (after->kind() != Kind::List) {
        error(after->loc(), "'after' must be a list of operation names");
        continue;
      }
      for (const ConfigNode& a : after->items())
        if (int j = operationAt(a, "'after' of '" + m_.operations[i].name + "'"); j >= 0) m_.operations[i].after.push_back(static_cast<uint32_t>(j));
    }
    m_.precedes.assign(n, std::vector<char>(n, 0));
    for (size_t i = 0; i < n; ++i)
      for (uint32_t j : m_.operations[i].after) m_.precedes[j][i] = 1;
    for (size_t k = 0; k < n; ++k)  // Floyd–Warshall closure: models have tens of operations
      for (size_t i = 0; i < n; ++i)
        if (m_.precedes[i][k])
          for (size_t j = 0; j < n; ++j)
            if (m_.precedes[k][j]) m_.precedes[i][j] = 1;
    for (size_t i = 0; i < n; ++i)
      if (m_.precedes[i][i]) {
        error(m_.operations[i].loc, "operation '" + m_.operations[i].name + "' must finish before itself: its 'after' constraints form a cycle");
        return;
      }
  }

  void readSequences(ConfigReader& top) {
    const ConfigNode* n = top.child("sequences");
    if (!n) return;
    if (n->kind() != Kind::List) {
      error(n->loc(), "'sequences' must be a list of { name, order }");
      return;
    }
    for (const ConfigNode& item : n->items()) readSequence(item);
  }

  void readSequence(const ConfigNode& item) {
    ConfigReader r(item, diags_, "sequence");
    UserSequence s;
    s.loc = item.loc();
    s.name = r.requireString("name");
    Candidate& c = s.candidate;
    std::string waits = r.optString("waits", "needed");
    if (waits == "serial") c.waits = WaitRule::Serial;
    else if (waits != "needed") error(item.find("waits")->loc(), "'waits' is '" + waits + "', expected needed or serial");
    c.ignoreResources = r.optBool("ignore_resources", false);
    const size_t n = m_.operations.size();
    c.choice.assign(n, 0);
    std::vector<char> listed(n, 0);
    const ConfigNode* order = r.child("order");
    if (!order || order->kind() != Kind::List) {
      error(order ? order->loc() : item.loc(), "sequence '" + s.name + "' needs 'order', the list of its operations");
      return;
    }
    for (const ConfigNode& o : order->items()) {
      int i = operationAt(o, "sequence '" + s.name + "'");
      if (i < 0) continue;
      if (listed[i]) error(o.loc(), "sequence '" + s.name + "' lists '" + o.scalar() + "' twice");
      listed[i] = 1;
      for (uint32_t before : c.order)
        if (m_.precedes[i][before])
          error(o.loc(), "sequence '" + s.name + "' lists '" + o.scalar() + "' after '" + m_.operations[before].name + "', which must come after it");
      c.order.push_back(static_cast<uint32_t>(i));
    }
    for (size_t i = 0; i < n; ++i) {
      if (listed[i]) continue;
      if (!m_.operations[i].optional) error(order->loc(), "sequence '" + s.name + "' leaves out '" + m_.operations[i].name + "', which is not optional");
      c.choice[i] = kSkipped;
      c.order.push_back(static_cast<uint32_t>(i));
    }
    if (const ConfigNode* choose = r.child("choose")) readChoices(*choose, s);
    m_.sequences.push_back(std::move(s));
    r.rejectUnknownKeys();
  }

  void readChoices(const ConfigNode& choose, UserSequence& s) {
    if (choose.kind() != Kind::Map) {
      error(choose.loc(), "'choose' must map operations to the name of an alternative");
      return;
    }
    for (const auto& [opName, alt] : choose.entries()) {
      int i = m_.operationIndex(opName);
      if (i < 0) {
        error(choose.keyLoc(opName), "'choose' names '" + opName + "', which is no operation of the model");
        continue;
      }
      const auto& alts = m_.operations[i].alternatives;
      auto it = std::ranges::find_if(alts, [&](const Alternative& a) { return a.name == alt.scalar(); });
      std::string known;
      for (const Alternative& a : alts) known += (known.empty() ? "" : ", ") + a.name;
      if (it == alts.end()) error(alt.loc(), "operation '" + opName + "' has no alternative '" + alt.scalar() + "' (expected one of: " + known + ")");
      else if (s.candidate.choice[i] != kSkipped) s.candidate.choice[i] = static_cast<int>(it - alts.begin());
    }
  }

  ProcessModel& m_;
  Diagnostics& diags_;
  std::vector<const ConfigNode*> afterNames_;  // per operation, its `after:` node
};

}  // namespace

std::optional<ProcessModel> readProcessModel(const std::string& path, SourceManager& sources, Diagnostics& diags) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    diags.error(celldiag::C002, {}, "cannot read process model '" + path + "'");
    return std::nullopt;
  }
  std::stringstream text;
  text << in.rdbuf();
  ConfigNode root;
  if (!cell::parseYaml(path, text.str(), sources, diags, root)) return std::nullopt;
  ProcessModel m;
  m.file = path;
  if (root.kind() != ConfigNode::Kind::Map) {
    diags.error(celldiag::C070, root.loc(), "a process model is a map with 'cell', 'job_list', 'device_numbers' and 'operations'");
    return std::nullopt;
  }
  ModelReader(m, diags).read(root);
  diags.sortByLocation();
  if (diags.hasErrors()) return std::nullopt;
  return m;
}

std::string checkCandidate(const ProcessModel& m, const Candidate& c) {
  const size_t n = m.operations.size();
  if (c.order.size() != n || c.choice.size() != n) return "the candidate does not place every operation once";
  std::vector<char> seen(n, 0);
  std::vector<uint32_t> placed;
  for (uint32_t i : c.order) {
    if (i >= n || seen[i]) return "the candidate does not place every operation once";
    seen[i] = 1;
    const Operation& op = m.operations[i];
    if (c.choice[i] == kSkipped) {
      if (!op.optional) return "operation '" + op.name + "' is left out but not optional";
      continue;
    }
    if (c.choice[i] < 0 || static_cast<size_t>(c.choice[i]) >= op.alternatives.size())
      return "operation '" + op.name + "' has no alternative " + std::to_string(c.choice[i]);
    for (uint32_t before : placed)
      if (m.precedes[i][before]) return "'" + op.name + "' comes before '" + m.operations[before].name + "' but must follow it";
    placed.push_back(i);
  }
  return {};
}

}  // namespace virtcom::optimize

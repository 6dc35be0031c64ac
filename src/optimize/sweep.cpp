// Sweep files, their points, and one evaluation per point on an edited copy of the cell's tree.
#include "optimize/sweep.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>

#include "cell/yaml_config.hpp"
#include "core/cell_diagnostic_codes.hpp"
#include "core/config_node.hpp"

namespace virtcom::optimize {

constexpr double kMaxTimeLimitSeconds = 9e9;

std::optional<SweepSpec> readSweep(const std::string& path, SourceManager& sources, Diagnostics& diags) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    diags.error(celldiag::C002, {}, "cannot read sweep file '" + path + "'");
    return std::nullopt;
  }
  std::stringstream text;
  text << in.rdbuf();
  ConfigNode root;
  if (!cell::parseYaml(path, text.str(), sources, diags, root)) return std::nullopt;
  SweepSpec s;
  s.file = path;
  ConfigReader top(root, diags, "the sweep file");
  if (std::string c = top.requireString("cell"); !c.empty()) s.cellFile = (s.file.parent_path() / c).lexically_normal().string();
  if (const ConfigNode* set = top.child("set"))
    for (const auto& [name, value] : set->entries()) s.presets.emplace_back(name, value.scalar());
  const std::string sampling = top.optString("sampling", "grid");
  s.random = sampling == "random";
  if (!s.random && sampling != "grid") diags.error(celldiag::C070, root.find("sampling")->loc(), "'sampling' is '" + sampling + "', expected grid or random");
  // Read signed: a negative count cast to size_t would ask for ~2^64 points.
  const int64_t samples = top.optInt("samples", 0);
  if (samples < 0)
    diags.error(celldiag::C070, root.find("samples")->loc(), "'samples' is " + std::to_string(samples) + ", expected a positive number of points");
  else s.samples = static_cast<size_t>(samples);
  if (s.random && samples == 0) diags.error(celldiag::C070, root.loc(), "'sampling: random' needs 'samples', the number of points");
  s.seed = static_cast<uint64_t>(top.optInt("seed", 1));
  if (top.has("time_limit")) {
    // int64 nanoseconds hold about 292 years; beyond that the conversion is undefined (fuzz_sweep_file).
    const double seconds = top.optQuantity("time_limit", Dimension::Time, 0);
    if (!std::isfinite(seconds) || std::abs(seconds) > kMaxTimeLimitSeconds)
      diags.error(celldiag::C070, root.find("time_limit")->loc(), "'time_limit' is out of range, expected at most 9e9 s");
    else s.timeLimitNs = static_cast<int64_t>(seconds * 1e9 + 0.5);
  }
  const ConfigNode* params = top.child("parameters");
  if (!params || params->kind() != ConfigNode::Kind::Map || params->entries().empty())
    diags.error(celldiag::C070, params ? params->loc() : root.loc(), "the sweep needs 'parameters:', e.g. { Robot1.max_speed: [800 mm/s, 1150 mm/s] }");
  else
    for (const auto& [name, values] : params->entries()) {
      SweepParameter p{name, {}, params->keyLoc(name)};
      if (values.kind() != ConfigNode::Kind::List || values.items().empty())
        diags.error(celldiag::C070, values.loc(), "parameter '" + name + "' needs a list of values");
      else
        for (const ConfigNode& v : values.items()) p.values.push_back(v.scalar());
      s.parameters.push_back(std::move(p));
    }
  top.rejectUnknownKeys();
  diags.sortByLocation();
  if (diags.hasErrors()) return std::nullopt;
  return s;
}

std::vector<std::vector<size_t>> sweepPoints(const SweepSpec& spec) {
  std::vector<std::vector<size_t>> points;
  if (spec.random) {
    std::mt19937_64 rng(spec.seed);
    for (size_t i = 0; i < spec.samples; ++i) {
      std::vector<size_t> at;
      for (const SweepParameter& p : spec.parameters) at.push_back(static_cast<size_t>(rng() % p.values.size()));
      points.push_back(std::move(at));
    }
    return points;
  }
  std::vector<size_t> at(spec.parameters.size(), 0);
  while (true) {
    points.push_back(at);
    size_t k = at.size();
    while (k > 0 && ++at[k - 1] == spec.parameters[k - 1].values.size()) at[--k] = 0;
    if (k == 0) return points;
  }
}

std::unique_ptr<Sweeper> Sweeper::create(const SweepSpec& spec, SourceManager& sources, Diagnostics& diags) {
  std::unique_ptr<Sweeper> s(new Sweeper(spec));
  s->template_ = cell::loadCellTemplate(spec.cellFile, sources, diags);
  if (!s->template_) return nullptr;
  const bc::Module* m = s->template_->module.get();
  if (!m) {
    diags.error(celldiag::C070, {}, "the cell '" + spec.cellFile + "' has no soft PLC ('plc: sources')");
    return nullptr;
  }
  const ConfigNode* devices = s->template_->root.find("devices");
  std::vector<uint8_t> scratch(m->memorySize(), 0);
  for (const SweepParameter& p : spec.parameters) {
    int device = -1;
    const std::string owner = p.name.substr(0, p.name.find('.'));
    for (size_t i = 0; devices && i < devices->items().size(); ++i)
      if (const ConfigNode* n = devices->items()[i].find("name"); n && n->scalar() == owner) device = static_cast<int>(i);
    s->deviceIndex_.push_back(device);
    s->variables_.push_back(device < 0 ? bc::resolveVariable(*m, p.name) : std::nullopt);
    if (device < 0 && !s->variables_.back())
      diags.error(celldiag::C070, p.loc, "'" + p.name + "' names neither a device parameter of the cell (DEVICE.key) nor a PLC variable");
    else if (device < 0)
      for (const std::string& v : p.values)
        if (std::string problem = bc::writeValueFromText(*m, *s->variables_.back(), v, scratch.data()); !problem.empty())
          diags.error(celldiag::C070, p.loc, "'" + p.name + "': " + problem);
  }
  // Every device value once, in a cell of its own: a value the device refuses ('fast' for a
  // speed) is reported here, at the sweep file, rather than as a failed point.
  for (size_t p = 0; p < spec.parameters.size() && !diags.hasErrors(); ++p) {
    if (s->deviceIndex_[p] < 0) continue;
    for (size_t v = 0; v < spec.parameters[p].values.size(); ++v) {
      std::vector<size_t> at(spec.parameters.size(), 0);
      at[p] = v;
      if (!cell::instantiateCell(*s->template_, s->editedRoot(at), sources, diags)) break;
    }
  }
  for (const auto& [name, value] : spec.presets) {
    auto ref = bc::resolveVariable(*m, name);
    if (!ref) diags.error(celldiag::C070, {}, "'set': the PLC has no variable '" + name + "'");
    else s->presets_.emplace_back(*ref, value);
  }
  if (diags.hasErrors()) return nullptr;
  return s;
}

// The cell's tree with the point's device parameters written into their device entries.
ConfigNode Sweeper::editedRoot(const std::vector<size_t>& at) const {
  const ConfigNode& root = template_->root;
  const ConfigNode& devices = *root.find("devices");
  ConfigNode list = ConfigNode::makeList(devices.loc());
  for (size_t i = 0; i < devices.items().size(); ++i) {
    const ConfigNode& d = devices.items()[i];
    ConfigNode entry = d;
    for (size_t p = 0; p < at.size(); ++p) {
      if (deviceIndex_[p] != static_cast<int>(i)) continue;
      const SweepParameter& param = spec_.parameters[p];
      const std::string key = param.name.substr(param.name.find('.') + 1);
      ConfigNode edited = ConfigNode::makeMap(entry.loc());
      bool found = false;
      for (const auto& [k, v] : entry.entries()) {
        found |= k == key;
        edited.add(k, entry.keyLoc(k), k == key ? ConfigNode::makeScalar(param.values[at[p]], param.loc) : v);
      }
      if (!found) edited.add(key, param.loc, ConfigNode::makeScalar(param.values[at[p]], param.loc));
      entry = std::move(edited);
    }
    list.push(std::move(entry));
  }
  ConfigNode out = ConfigNode::makeMap(root.loc());
  for (const auto& [key, value] : root.entries()) out.add(key, root.keyLoc(key), key == "devices" ? list : value);
  return out;
}

std::vector<std::string> Sweeper::values(const std::vector<size_t>& at) const {
  std::vector<std::string> out;
  for (size_t p = 0; p < at.size(); ++p) out.push_back(spec_.parameters[p].values[at[p]]);
  return out;
}

SweepRow Sweeper::evaluate(size_t point, const std::vector<size_t>& at) const {
  SweepRow row;
  row.point = point;
  row.values = values(at);
  const bc::Module& m = *template_->module;
  runInstance(*template_, editedRoot(at),
              [&](uint8_t* memory) {
                for (const auto& [ref, value] : presets_) bc::writeValueFromText(m, ref, value, memory);
                for (size_t p = 0; p < at.size(); ++p)
                  if (variables_[p]) bc::writeValueFromText(m, *variables_[p], spec_.parameters[p].values[at[p]], memory);
              },
              spec_.timeLimitNs, row.eval);
  return row;
}

namespace {

std::string csvField(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace

std::string sweepCsv(const SweepSpec& spec, const std::vector<SweepRow>& rows) {
  std::string s = "point";
  for (const SweepParameter& p : spec.parameters) {
    s += ',';
    s += csvField(p.name);
  }
  s += ",cycle_s,energy_J,result\n";
  for (const SweepRow& r : rows) {
    s += std::to_string(r.point);
    for (const std::string& v : r.values) {
      s += ',';
      s += csvField(v);
    }
    char kpis[64];
    std::snprintf(kpis, sizeof kpis, ",%.3f,%.1f,ok", static_cast<double>(r.eval.cycleNs) * 1e-9, r.eval.energyJ);
    if (r.eval.feasible) {
      s += kpis;
    } else {
      s += ",,,";
      s += csvField(r.eval.reason);
    }
    s += "\n";
  }
  return s;
}

}  // namespace virtcom::optimize

#include "core/config_node.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>

#include "core/cell_diagnostic_codes.hpp"
#include "core/duration_units.hpp"

namespace virtcom {

const char* dimensionName(Dimension d) {
  switch (d) {
    case Dimension::Length: return "a length (e.g. 250 mm)";
    case Dimension::Time: return "a duration (e.g. 2 s, 150 ms)";
    case Dimension::Speed: return "a speed (e.g. 500 mm/s)";
    case Dimension::Acceleration: return "an acceleration (e.g. 2000 mm/s^2)";
    case Dimension::Power: return "a power (e.g. 150 W)";
    case Dimension::Energy: return "an energy (e.g. 20 J)";
    case Dimension::Force: return "a force (e.g. 5 kN)";
    case Dimension::Torque: return "a torque (e.g. 12 Nm)";
    case Dimension::Mass: return "a mass (e.g. 2.5 kg)";
    case Dimension::Angle: return "an angle (e.g. 90 deg)";
    case Dimension::Frequency: return "a frequency (e.g. 50 Hz)";
    case Dimension::Volume: return "a volume (e.g. 500 l)";
    case Dimension::VolumeFlow: return "a volume flow (e.g. 20 l/min)";
    case Dimension::Temperature: return "a temperature (e.g. 80 degC)";
    case Dimension::ThermalConductance: return "a heat loss per kelvin (e.g. 15 W/K)";
    case Dimension::Density: return "a density (e.g. 1000 kg/m3)";
    case Dimension::SpecificHeat: return "a specific heat (e.g. 4186 J/(kg*K))";
    case Dimension::Ratio: return "a percentage (e.g. 95 %)";
    case Dimension::Dimensionless: return "a number";
  }
  return "a value";
}

namespace {
struct Unit {
  const char* name;
  Dimension dim;
  double factor;
};
// Every accepted unit spelling but those of durations, which come from kDurationUnits.
constexpr Unit kUnits[] = {
    {"mm", Dimension::Length, 1e-3},         {"cm", Dimension::Length, 1e-2},
    {"m", Dimension::Length, 1.0},           {"mm/s", Dimension::Speed, 1e-3},
    {"m/s", Dimension::Speed, 1.0},          {"m/min", Dimension::Speed, 1.0 / 60},
    {"mm/s^2", Dimension::Acceleration, 1e-3}, {"mm/s2", Dimension::Acceleration, 1e-3},
    {"m/s^2", Dimension::Acceleration, 1.0}, {"m/s2", Dimension::Acceleration, 1.0},
    {"W", Dimension::Power, 1.0},            {"kW", Dimension::Power, 1e3},
    {"J", Dimension::Energy, 1.0},           {"kJ", Dimension::Energy, 1e3},
    {"Wh", Dimension::Energy, 3600.0},       {"N", Dimension::Force, 1.0},
    {"kN", Dimension::Force, 1e3},           {"Nm", Dimension::Torque, 1.0},
    {"N*m", Dimension::Torque, 1.0},         {"kg", Dimension::Mass, 1.0},
    {"g", Dimension::Mass, 1e-3},            {"deg", Dimension::Angle, 3.14159265358979323846 / 180},
    {"rad", Dimension::Angle, 1.0},          {"Hz", Dimension::Frequency, 1.0},
    {"l", Dimension::Volume, 1e-3},          {"ml", Dimension::Volume, 1e-6},
    {"m3", Dimension::Volume, 1.0},          {"l/s", Dimension::VolumeFlow, 1e-3},
    {"l/min", Dimension::VolumeFlow, 1e-3 / 60}, {"m3/h", Dimension::VolumeFlow, 1.0 / 3600},
    {"m3/s", Dimension::VolumeFlow, 1.0},    {"degC", Dimension::Temperature, 1.0},
    {"°C", Dimension::Temperature, 1.0},     {"W/K", Dimension::ThermalConductance, 1.0},
    {"kg/m3", Dimension::Density, 1.0},      {"kg/l", Dimension::Density, 1e3},
    {"J/(kg*K)", Dimension::SpecificHeat, 1.0}, {"kJ/(kg*K)", Dimension::SpecificHeat, 1e3},
    {"%", Dimension::Ratio, 1e-2},
};
// The unit spelled exactly `name`, of any dimension; nullopt if none. Durations convert as
// ns / 1e9, which rounds to the same double as the decimal factors (1e-3 for ms).
std::optional<Unit> findUnit(std::string_view name) {
  for (const Unit& unit : kUnits)
    if (name == unit.name) return unit;
  if (const DurationUnit* unit = quantityDurationUnit(name))
    return Unit{"", Dimension::Time, static_cast<double>(unit->ns) / 1e9};
  return std::nullopt;
}

}  // namespace

std::string parseQuantity(const std::string& text, Dimension dim, double& si) {
  const char* begin = text.c_str();
  char* end = nullptr;
  double value = std::strtod(begin, &end);
  if (end == begin) return "expected " + std::string(dimensionName(dim)) + ", found '" + text + "'";
  std::string unit(end);
  unit.erase(std::remove_if(unit.begin(), unit.end(), [](unsigned char c) { return std::isspace(c); }), unit.end());
  if (dim == Dimension::Dimensionless) {
    if (!unit.empty()) return "expected a plain number, found '" + text + "'";
    si = value;
    return {};
  }
  if (unit.empty()) return "'" + text + "' needs a unit: expected " + dimensionName(dim);
  if (std::optional<Unit> u = findUnit(unit)) {
    if (u->dim != dim) return "'" + text + "' is not " + dimensionName(dim);
    si = value * u->factor;
    return {};
  }
  return "unknown unit '" + unit + "' in '" + text + "': expected " + dimensionName(dim);
}

ConfigNode ConfigNode::makeScalar(std::string value, SourceLocation loc) {
  ConfigNode n;
  n.kind_ = Kind::Scalar;
  n.scalar_ = std::move(value);
  n.loc_ = loc;
  return n;
}

ConfigNode ConfigNode::makeMap(SourceLocation loc) {
  ConfigNode n;
  n.kind_ = Kind::Map;
  n.loc_ = loc;
  return n;
}

ConfigNode ConfigNode::makeList(SourceLocation loc) {
  ConfigNode n;
  n.kind_ = Kind::List;
  n.loc_ = loc;
  return n;
}

void ConfigNode::add(std::string key, SourceLocation keyLoc, ConfigNode value) {
  entries_.emplace_back(std::move(key), std::move(value));
  keyLocs_.push_back(keyLoc);
}

void ConfigNode::push(ConfigNode value) { items_.push_back(std::move(value)); }

const ConfigNode* ConfigNode::find(const std::string& key) const {
  for (const auto& [k, v] : entries_)
    if (k == key) return &v;
  return nullptr;
}

SourceLocation ConfigNode::keyLoc(const std::string& key) const {
  for (size_t i = 0; i < entries_.size(); ++i)
    if (entries_[i].first == key) return keyLocs_[i];
  return loc_;
}

ConfigReader::ConfigReader(const ConfigNode& node, Diagnostics& diags, std::string what)
    : node_(node), diags_(diags), what_(std::move(what)) {
  if (node.kind() != ConfigNode::Kind::Map) error(node.loc(), what_ + " must be a mapping of `key: value` entries");
}

void ConfigReader::error(SourceLocation loc, std::string message) {
  ok_ = false;
  diags_.error(celldiag::C010, loc, std::move(message));
}

const ConfigNode* ConfigReader::child(const std::string& key) {
  used_.push_back(key);
  return node_.find(key);
}

const ConfigNode* ConfigReader::need(const std::string& key) {
  const ConfigNode* n = child(key);
  if (!n) error(node_.loc(), what_ + " needs '" + key + "'");
  return n;
}

static bool scalarOr(ConfigReader& r, const ConfigNode* n, const std::string& key) {
  if (n && n->kind() != ConfigNode::Kind::Scalar) {
    r.error(n->loc(), "'" + key + "' must be a single value");
    return false;
  }
  return n != nullptr;
}

std::string ConfigReader::requireString(const std::string& key) {
  const ConfigNode* n = need(key);
  return scalarOr(*this, n, key) ? n->scalar() : std::string();
}

std::string ConfigReader::optString(const std::string& key, const std::string& fallback) {
  const ConfigNode* n = child(key);
  return scalarOr(*this, n, key) ? n->scalar() : fallback;
}

double ConfigReader::requireQuantity(const std::string& key, Dimension dim) {
  const ConfigNode* n = need(key);
  if (!scalarOr(*this, n, key)) return 0;
  double v = 0;
  std::string problem = parseQuantity(n->scalar(), dim, v);
  if (!problem.empty()) error(n->loc(), "'" + key + "': " + problem);
  return v;
}

double ConfigReader::optQuantity(const std::string& key, Dimension dim, double fallbackSi) {
  if (!node_.has(key)) {
    used_.push_back(key);
    return fallbackSi;
  }
  return requireQuantity(key, dim);
}

double ConfigReader::requireNumber(const std::string& key) { return requireQuantity(key, Dimension::Dimensionless); }

double ConfigReader::optNumber(const std::string& key, double fallback) {
  return optQuantity(key, Dimension::Dimensionless, fallback);
}

int64_t ConfigReader::requireInt(const std::string& key) {
  const ConfigNode* n = need(key);
  if (!scalarOr(*this, n, key)) return 0;
  char* end = nullptr;
  long long v = std::strtoll(n->scalar().c_str(), &end, 10);
  if (end == n->scalar().c_str() || *end != '\0') {
    error(n->loc(), "'" + key + "' must be a whole number, found '" + n->scalar() + "'");
    return 0;
  }
  return v;
}

int64_t ConfigReader::optInt(const std::string& key, int64_t fallback) {
  if (!node_.has(key)) {
    used_.push_back(key);
    return fallback;
  }
  return requireInt(key);
}

bool ConfigReader::optBool(const std::string& key, bool fallback) {
  const ConfigNode* n = child(key);
  if (!scalarOr(*this, n, key)) return fallback;
  const std::string& s = n->scalar();
  if (s == "true" || s == "yes" || s == "on") return true;
  if (s == "false" || s == "no" || s == "off") return false;
  error(n->loc(), "'" + key + "' must be true or false, found '" + s + "'");
  return fallback;
}

std::vector<double> ConfigReader::requireVector(const std::string& key, Dimension dim, size_t count) {
  std::vector<double> out;
  const ConfigNode* n = need(key);
  if (!n) return std::vector<double>(count, 0.0);
  if (n->kind() == ConfigNode::Kind::List) {
    for (const auto& item : n->items()) {
      double v = 0;
      std::string problem = item.kind() == ConfigNode::Kind::Scalar ? parseQuantity(item.scalar(), dim, v) : "expected a value";
      if (!problem.empty()) error(item.loc(), "'" + key + "': " + problem);
      out.push_back(v);
    }
  } else if (n->kind() == ConfigNode::Kind::Scalar) {
    // "100, 250, 0 mm": one unit after the last number applies to all of them
    std::string text = n->scalar();
    size_t unitAt = text.find_last_of("0123456789.") + 1;
    std::string unit = unitAt <= text.size() ? text.substr(unitAt) : "";
    std::string numbers = text.substr(0, unitAt);
    for (auto& c : numbers)
      if (c == ',') c = ' ';
    const char* p = numbers.c_str();
    char* end = nullptr;
    while (true) {
      double v = std::strtod(p, &end);
      if (end == p) break;
      double si = 0;
      std::string problem = parseQuantity(std::to_string(v) + unit, dim, si);
      if (!problem.empty()) {
        error(n->loc(), "'" + key + "': " + problem);
        break;
      }
      out.push_back(si);
      p = end;
    }
  } else {
    error(n->loc(), "'" + key + "' must be a list such as [100 mm, 250 mm, 0 mm] or \"100, 250, 0 mm\"");
  }
  if (out.size() != count) {
    error(n->loc(), "'" + key + "' needs " + std::to_string(count) + " values, found " + std::to_string(out.size()));
    out.resize(count, 0.0);
  }
  return out;
}

void ConfigReader::rejectUnknownKeys() {
  for (const auto& [k, v] : node_.entries())
    if (std::find(used_.begin(), used_.end(), k) == used_.end()) {
      std::string known;
      std::vector<std::string> seen;
      for (const auto& u : used_) {
        if (std::find(seen.begin(), seen.end(), u) != seen.end()) continue;
        seen.push_back(u);
        known += (known.empty() ? "" : ", ") + u;
      }
      ok_ = false;
      diags_.error(celldiag::C011, node_.keyLoc(k), "unknown key '" + k + "' in " + what_ + " (expected one of: " + known + ")");
    }
}

}  // namespace virtcom

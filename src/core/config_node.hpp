#pragma once
// A configuration tree (maps, lists, scalars) where every node knows its file position, so a
// device factory can report `cell.yaml:12:7: error[C010]: ...` without knowing YAML. The cell
// loader builds it from YAML; devices read their parameters through the typed getters below,
// which also parse quantities with explicit units ("500 mm/s", "2 s", "150 W").
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/diagnostics.hpp"

namespace virtcom {

// Physical dimensions a parameter may have; values are converted to SI base units
// (m, s, W, J, N, N*m, kg, m/s, m/s^2, rad, Hz, rpm stays rpm).
// Temperatures are kept in degrees Celsius (not kelvin): an offset scale, so only its own units
// (`degC`, `°C`) convert to it. A ratio is a fraction (`95 %` is 0.95).
enum class Dimension {
  Length, Time, Speed, Acceleration, Power, Energy, Force, Torque, Mass, Angle, Frequency,
  Volume, VolumeFlow, Temperature, ThermalConductance, Density, SpecificHeat, Ratio, Dimensionless
};
const char* dimensionName(Dimension d);
// Parses "500 mm/s" (number, optional spaces, unit) into SI. Error text if the unit is missing,
// unknown or of another dimension; empty on success.
std::string parseQuantity(const std::string& text, Dimension dim, double& si);

class ConfigNode {
 public:
  enum class Kind { Null, Scalar, Map, List };

  Kind kind() const { return kind_; }
  SourceLocation loc() const { return loc_; }
  const std::string& scalar() const { return scalar_; }
  // Map entries in file order.
  const std::vector<std::pair<std::string, ConfigNode>>& entries() const { return entries_; }
  const std::vector<ConfigNode>& items() const { return items_; }
  // Location of a map key (for "unknown key" errors).
  SourceLocation keyLoc(const std::string& key) const;
  const ConfigNode* find(const std::string& key) const;
  bool has(const std::string& key) const { return find(key) != nullptr; }

  // Builders (used by the loader and by tests).
  static ConfigNode makeScalar(std::string value, SourceLocation loc);
  static ConfigNode makeMap(SourceLocation loc);
  static ConfigNode makeList(SourceLocation loc);
  void add(std::string key, SourceLocation keyLoc, ConfigNode value);
  void push(ConfigNode value);

 private:
  Kind kind_ = Kind::Null;
  SourceLocation loc_;
  std::string scalar_;
  std::vector<std::pair<std::string, ConfigNode>> entries_;
  std::vector<SourceLocation> keyLocs_;
  std::vector<ConfigNode> items_;
};

// Typed, reporting access to one map node. Every getter reports a diagnostic (code C0xx) at
// the right position and returns a fallback on error, so a loader can collect every mistake
// in one pass; `ok()` tells whether anything was wrong. Keys that were never read can be
// reported as unknown with `rejectUnknownKeys()` (catches typos such as `max_sped`).
class ConfigReader {
 public:
  ConfigReader(const ConfigNode& node, Diagnostics& diags, std::string what);

  bool has(const std::string& key) const { return node_.has(key); }
  const ConfigNode* child(const std::string& key);  // marks the key used; null if absent
  std::string requireString(const std::string& key);
  std::string optString(const std::string& key, const std::string& fallback);
  double requireQuantity(const std::string& key, Dimension dim);
  double optQuantity(const std::string& key, Dimension dim, double fallbackSi);
  double requireNumber(const std::string& key);
  double optNumber(const std::string& key, double fallback);
  int64_t requireInt(const std::string& key);
  int64_t optInt(const std::string& key, int64_t fallback);
  bool optBool(const std::string& key, bool fallback);
  // `count` quantities: a list [100 mm, 250 mm, 0 mm] or one string "100, 250, 0 mm".
  std::vector<double> requireVector(const std::string& key, Dimension dim, size_t count);
  void rejectUnknownKeys();

  void error(SourceLocation loc, std::string message);
  bool ok() const { return ok_; }
  const ConfigNode& node() const { return node_; }
  Diagnostics& diags() { return diags_; }

 private:
  const ConfigNode* need(const std::string& key);
  const ConfigNode& node_;
  Diagnostics& diags_;
  std::string what_;
  std::vector<std::string> used_;
  bool ok_ = true;
};

}  // namespace virtcom

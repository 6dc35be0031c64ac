#include "plant/config_helpers.hpp"

#include <cstdlib>

#include "plant/motion_profile.hpp"

namespace virtcom::plant {

int64_t requireDurationNs(ConfigReader& cfg, const std::string& key) {
  const int64_t ns = secondsToNs(cfg.requireQuantity(key, Dimension::Time));
  // No device parameter is a negative time; it is reported at the value, with the key's name.
  if (ns < 0) cfg.error(cfg.node().find(key)->loc(), "'" + key + "' must not be negative (got '" + cfg.node().find(key)->scalar() + "')");
  return ns;
}

int64_t optDurationNs(ConfigReader& cfg, const std::string& key, int64_t fallbackNs) {
  if (!cfg.has(key)) {
    cfg.child(key);  // mark as known for rejectUnknownKeys
    return fallbackNs;
  }
  return requireDurationNs(cfg, key);
}

std::vector<uint32_t> optFactList(ConfigReader& cfg, const std::string& key, World& world) {
  std::vector<uint32_t> out;
  const ConfigNode* n = cfg.child(key);
  if (!n) return out;
  if (n->kind() == ConfigNode::Kind::Scalar) {
    if (!n->scalar().empty()) out.push_back(world.fact(n->scalar()));
    return out;
  }
  if (n->kind() != ConfigNode::Kind::List) {
    cfg.error(n->loc(), "'" + key + "' must be a list of fact names such as [pinPlaced, insertLocked]");
    return out;
  }
  for (const auto& item : n->items()) {
    if (item.kind() != ConfigNode::Kind::Scalar || item.scalar().empty()) {
      cfg.error(item.loc(), "'" + key + "': expected a fact name");
      continue;
    }
    out.push_back(world.fact(item.scalar()));
  }
  return out;
}

int32_t vesselRef(ConfigReader& cfg, const std::string& key, World& world, bool required) {
  const ConfigNode* n = cfg.child(key);
  if (!n) {
    if (required) cfg.error(cfg.node().loc(), "missing '" + key + "' (the name of a tank device)");
    return -1;
  }
  if (n->kind() != ConfigNode::Kind::Scalar || n->scalar().empty()) {
    cfg.error(n->loc(), "'" + key + "' must name a tank device");
    return -1;
  }
  return static_cast<int32_t>(world.vessel(n->scalar(), n->loc()));
}

double requirePositive(ConfigReader& cfg, const std::string& key, Dimension dim) {
  const double v = cfg.requireQuantity(key, dim);
  const ConfigNode* n = cfg.node().find(key);
  if (n && n->kind() == ConfigNode::Kind::Scalar && !(v > 0)) cfg.error(n->loc(), "'" + key + "' must be greater than 0");
  return v;
}

double optPositive(ConfigReader& cfg, const std::string& key, Dimension dim, double fallbackSi) {
  if (!cfg.has(key)) return cfg.optQuantity(key, dim, fallbackSi);
  return requirePositive(cfg, key, dim);
}

bool parseCommandNumber(ConfigReader& cfg, const std::string& key, SourceLocation loc, int32_t& out) {
  char* end = nullptr;
  long v = std::strtol(key.c_str(), &end, 10);
  if (key.empty() || *end != '\0' || v < 1 || v > 32767) {
    cfg.error(loc, "command number '" + key + "' must be a whole number from 1 to 32767");
    return false;
  }
  out = static_cast<int32_t>(v);
  return true;
}

const ConfigNode* mapChild(ConfigReader& cfg, const std::string& key, bool required) {
  const ConfigNode* n = cfg.child(key);
  if (!n) {
    if (required) cfg.error(cfg.node().loc(), "missing '" + key + "' (a map)");
    return nullptr;
  }
  if (n->kind() != ConfigNode::Kind::Map) {
    cfg.error(n->loc(), "'" + key + "' must be a map of `name: value` entries");
    return nullptr;
  }
  return n;
}

std::string joinNames(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

}  // namespace virtcom::plant

#pragma once
// Load-time helpers shared by the device factories: numbered command tables, fact lists,
// durations in ns. Everything reports through ConfigReader (file:line:col) and never throws.
#include <cstdint>
#include <string>
#include <vector>

#include "core/config_node.hpp"
#include "plant/world.hpp"

namespace virtcom::plant {

// A duration parameter as integer nanoseconds (required / optional with a fallback in ns). A
// negative value is an error at the value, naming the key.
int64_t requireDurationNs(ConfigReader& cfg, const std::string& key);
int64_t optDurationNs(ConfigReader& cfg, const std::string& key, int64_t fallbackNs);

// A list of world fact names (`[a, b]`, or one name), interned in `world`. Absent: empty.
std::vector<uint32_t> optFactList(ConfigReader& cfg, const std::string& key, World& world);

// Parses a command-number map key ("3") into `out`; reports at `loc` and returns false if the
// key is not a whole number in 1..32767 (the range of an INT procedure number, 0 = none).
bool parseCommandNumber(ConfigReader& cfg, const std::string& key, SourceLocation loc, int32_t& out);

// A map parameter (`procedures:`, `programs:`, ...): the node, or null with a diagnostic if the
// key is present but not a map. Absent and not required: null without a diagnostic.
const ConfigNode* mapChild(ConfigReader& cfg, const std::string& key, bool required);

// The vessel (tank) named by `key`, interned in `world` with the key's location so that the cell
// loader can report a name no tank defines; -1 if the key is absent (or, if `required`, after a
// diagnostic).
int32_t vesselRef(ConfigReader& cfg, const std::string& key, World& world, bool required);

// A quantity parameter that must be greater than 0 (reported at its value otherwise).
double requirePositive(ConfigReader& cfg, const std::string& key, Dimension dim);
double optPositive(ConfigReader& cfg, const std::string& key, Dimension dim, double fallbackSi);

// "a, b, c" joined for "expected one of" messages.
std::string joinNames(const std::vector<std::string>& names);

}  // namespace virtcom::plant

// Device parameter changes of scenario steps: editing a copy of the device's cell-file entry.
#include "scenario/parameter_change.hpp"

#include <algorithm>
#include <string_view>

#include "core/cell_diagnostic_codes.hpp"

namespace virtcom::scenario {

namespace {

// Keys of a device entry that are no parameters of its model.
constexpr std::string_view kNotParameters[] = {"name", "type", "wiring", "faults", "group", "model", "description"};

// `node` with `value` at `path` ("max_speed", "programs.1.press_time": keys of nested maps); a
// missing last key is added (the device's factory then rejects a key its type does not have).
// Sets `error` on a path that leads nowhere.
ConfigNode edited(const ConfigNode& node, std::string_view path, const ConfigNode& value, SourceLocation keyLoc, std::string& error) {
  const size_t dot = path.find('.');
  const std::string key(path.substr(0, dot));
  const std::string_view rest = dot == std::string_view::npos ? std::string_view{} : path.substr(dot + 1);
  const ConfigNode* child = node.kind() == ConfigNode::Kind::Map ? node.find(key) : nullptr;
  if (node.kind() != ConfigNode::Kind::Map || (!child && !rest.empty())) {
    error = "the device's entry has no '" + key + "' here";
    return node;
  }
  ConfigNode out = ConfigNode::makeMap(node.loc());
  for (const auto& [k, v] : node.entries()) {
    if (k != key) out.add(k, node.keyLoc(k), v);
    else if (rest.empty()) out.add(k, keyLoc, value);
    else out.add(k, node.keyLoc(k), edited(v, rest, value, keyLoc, error));
  }
  if (!child) out.add(key, keyLoc, value);
  return out;
}

}  // namespace

std::unique_ptr<plant::Device> ParameterEditor::edit(const std::string& name, SourceLocation keyLoc, const ConfigNode& value,
                                                     Diagnostics& diags, uint32_t& device) {
  const size_t dot = name.find('.');
  const std::string deviceName = name.substr(0, dot);
  auto found = std::ranges::find_if(cell_.devices, [&](const auto& d) { return d->name() == deviceName; });
  if (dot == std::string::npos || found == cell_.devices.end()) {
    std::string names;
    for (const auto& d : cell_.devices) names += (names.empty() ? "" : ", ") + d->name();
    diags.error(celldiag::C062, keyLoc, "'" + name + "': expected DEVICE.parameter with a device of the cell (" + names + ")");
    return nullptr;
  }
  const plant::Device& d = **found;
  const std::string path = name.substr(dot + 1);
  const std::string key = path.substr(0, path.find('.'));
  if (std::ranges::find(kNotParameters, key) != std::end(kNotParameters)) {
    diags.error(celldiag::C062, keyLoc, "'" + name + "': '" + key + "' is no parameter of the device's model");
    return nullptr;
  }
  if (!d.changesParameter(key)) {
    diags.error(celldiag::C062, keyLoc,
                "'" + name + "': a " + d.type() + " cannot change '" + key + "' during a run (docs/scenarios.md lists what each type can change)");
    return nullptr;
  }
  if (value.kind() != ConfigNode::Kind::Scalar) {
    diags.error(celldiag::C062, value.loc(), "'" + name + "': a changed parameter is one value, e.g. 800 mm/s");
    return nullptr;
  }
  device = static_cast<uint32_t>(found - cell_.devices.begin());
  std::string error;
  ConfigNode entry = edited(entries_[device], path, value, keyLoc, error);
  if (!error.empty()) {
    diags.error(celldiag::C062, keyLoc, "'" + name + "': " + error);
    return nullptr;
  }
  const size_t errorsBefore = diags.errorCount();
  ConfigReader cfg(entry, diags, "device");
  auto rebuilt = cell::createDeviceOfEntry(cfg, d.name(), d.type(), cell_.world);
  if (!rebuilt || diags.errorCount() != errorsBefore) return nullptr;
  entries_[device] = std::move(entry);
  return rebuilt;
}

}  // namespace virtcom::scenario

#pragma once
// A step's `parameter:` map (docs/scenarios.md "Steps"): `DEVICE.key: VALUE` changes a device
// parameter in the middle of a run. The device is built again from its cell-file entry with the
// value edited in, by the cell loader's own code, so the value is checked exactly as the cell
// file's (file:line:col at the scenario); when the step acts, the running device swaps
// parameters with it (plant::Device::swapParameters: at a tick boundary, no allocation).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "cell/cell.hpp"

namespace virtcom::scenario {

class ParameterEditor {
 public:
  explicit ParameterEditor(cell::Cell& cell) : cell_(cell), entries_(cell.deviceEntries) {}

  // The device named by `name` ("Robot1.max_speed", "Press.programs.1.press_time": the keys
  // of its cell-file entry down to the value) built with `value` there, on top of the
  // changes this editor made before (changes of one device build on the earlier ones of the
  // file); `device` = its index in Cell::devices. Null, with diagnostics, on a mistake.
  std::unique_ptr<plant::Device> edit(const std::string& name, SourceLocation keyLoc, const ConfigNode& value, Diagnostics& diags,
                                      uint32_t& device);

 private:
  cell::Cell& cell_;
  std::vector<ConfigNode> entries_;  // every device's entry with the changes so far
};

}  // namespace virtcom::scenario

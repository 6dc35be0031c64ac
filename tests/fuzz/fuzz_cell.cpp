// libFuzzer target for the whole cell file, as `virtcom run` reads it: YAML -> loadCell (the
// `extends:` base, the PLC sources compiled, `mapping:` files, devices, world, wiring, run
// conditions, `modbus:`, `plc: modbus:/ads:`, `hmi:`, `plan:`), then a short run of the loaded
// cell (at most kTicks base ticks, whatever its run settings say). The input is the cell file
// examples/drives/g120/fuzz_cell.yaml of the scratch tree (fuzz_scratch.hpp): a sibling of the
// drive example cells, so the checked-in seeds name the copy's PLC sources, mappings and base
// cells as the examples do. Inputs naming a file outside the tree are skipped.
// Finds crashes, leaks and UB in the loader and in the devices stepping on odd parameters; a
// rejected cell always says why.
#include <cstdint>

#include "cell/cell.hpp"
#include "fuzz_scratch.hpp"
#include "sim/simulation.hpp"

namespace {

constexpr int kTicks = 200;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const virtcom::fuzz::Scratch& scratch = virtcom::fuzz::Scratch::get();
  const std::string path = scratch.write(virtcom::fuzz::kCellInput, data, size);
  virtcom::SourceManager sources;
  virtcom::Diagnostics diags;
  virtcom::ConfigNode tree;
  const std::string text(reinterpret_cast<const char*>(data), size);
  if (virtcom::cell::parseYaml(path, text, sources, diags, tree) &&
      !scratch.namesOnlyInside(tree, std::filesystem::path(path).parent_path()))
    return -1;
  auto cell = virtcom::cell::loadCell(path, sources, diags);
  if (!cell) {
    if (!diags.hasErrors()) __builtin_trap();  // a rejected cell always says why
    return 0;
  }
  virtcom::sim::Simulation simulation(*cell, {});
  for (int tick = 0; tick < kTicks && simulation.step(); ++tick) {
  }
  return 0;
}

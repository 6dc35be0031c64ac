// Per-tick cost of the EPos positioning axis (telegram 111), of applying a UNIVERSAL_AXIS
// mapping (pack, the words the drive decodes, its reply, unpack) — the extra work of a mapped drive —
// and of the whole mapped axis as a cell steps it (tag bus, mapping, drive).
#include <benchmark/benchmark.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "cell/yaml_config.hpp"
#include "core/trace.hpp"
#include "drives/epos_axis.hpp"
#include "drives/mapped_ports.hpp"

namespace virtcom::bench {
namespace {

constexpr int64_t kStepNs = 1'000'000;

// Jog forward and backward (the direction flips every 2000 ticks), so the profile, the position
// loop, the monitoring and all status words stay busy.
void BM_DriveTickEpos111(benchmark::State& state) {
  drives::DriveCommon common;
  common.telegram = drives::TelegramId::Std111;
  drives::EposAxis drive("D", common, drives::EposParams{});
  int64_t now = 0;
  std::vector<uint32_t> words{0x043E, 0, 0, 0, 0x4000, 0, 100, 0x4000, 0x4000, 0};
  drive.exchange(words, now += kStepNs);
  words[0] = 0x043F;
  for (int i = 0; i < 100; ++i) drive.exchange(words, now += kStepNs);
  std::vector<uint32_t> jog1 = words, jog2 = words;
  jog1[0] = 0x053F;
  jog2[0] = 0x063F;
  uint64_t i = 0;
  for (auto _ : state) {
    drive.exchange((i++ / 2000) % 2 ? jog1 : jog2, now += kStepNs);
    benchmark::DoNotOptimize(drive.tx()[5]);
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));
}

std::shared_ptr<const drives::MappingSpec> bundledMapping(const char* name) {
  std::ifstream in(std::filesystem::path(VIRTCOM_SOURCE_DIR) / "lib" / "mappings" / name);
  std::stringstream text;
  text << in.rdbuf();
  SourceManager sources;
  Diagnostics diags;
  ConfigNode root;
  if (!cell::parseYaml(name, text.str(), sources, diags, root)) return nullptr;
  auto spec = drives::parseMapping(root, diags);
  return spec ? std::make_shared<const drives::MappingSpec>(std::move(*spec)) : nullptr;
}

// The mapping layer alone for telegram 111 (the largest image) when everything changes every
// tick: Control_* values to the words the drive decodes, and the reply words back to Status_*
// values (a mapped drive converts only what changed: BM_MappedAxisTickEpos111).
void BM_AxisMappingTelegram111(benchmark::State& state) {
  auto spec = bundledMapping("telegram111.yaml");
  if (!spec) {
    state.SkipWithError("lib/mappings/telegram111.yaml did not load");
    return;
  }
  drives::MappingRuntime runtime(*spec);
  drives::AxisSignalValues values{};
  values[static_cast<size_t>(drives::AxisSignal::Control_Start)] = 1;
  values[static_cast<size_t>(drives::AxisSignal::Control_GoalPosition)] = 70000;
  values[static_cast<size_t>(drives::AxisSignal::Control_OverridePosV)] = 50;
  drives::RawWords out{}, in{}, rx{}, tx{};
  tx[0] = 0x2F37;
  tx[5] = 70000;
  for (auto _ : state) {
    runtime.pack(values, out);
    runtime.toDrive(out, rx, ~0u);
    runtime.fromDrive(tx, in);
    runtime.unpack(in, values);
    benchmark::DoNotOptimize(rx[0]);
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));
}

// One cell tick of an EPos axis with `mapping: telegram111.yaml`, as the simulation steps it:
// the Control_* ports read from the tag bus, the mapping, the drive's bus cycle and integration
// step, the Status_* and Cfg_* ports written back. The same jog pattern as BM_DriveTickEpos111,
// commanded through the block's signals.
void BM_MappedAxisTickEpos111(benchmark::State& state) {
  drives::DriveCommon common;
  common.telegram = drives::TelegramId::Std111;
  common.mapping = bundledMapping("telegram111.yaml");
  if (!common.mapping) {
    state.SkipWithError("lib/mappings/telegram111.yaml did not load");
    return;
  }
  drives::EposAxis drive("D", common, drives::EposParams{});
  TagBus bus;
  for (size_t i = 0; i < drive.ports().size(); ++i)
    drive.bindPort(i, bus.add("D." + drive.ports()[i].name, drive.ports()[i].type));
  Trace trace;
  plant::World world(trace);
  drive.prepare(world, trace);
  const auto set = [&](const char* port, double v) { bus.setNumber(drive.tag(static_cast<size_t>(drive.portIndex(port))), v); };
  for (const char* on : {"Control_OFF2", "Control_OFF3", "Control_EnablePos", "Control_noJOB_STOP", "Control_NOSTOP",
                         "Control_ControlFromPLC", "Control_Start"})
    set(on, 1);
  set("Control_SpeedPosition", 100);
  for (const char* percent : {"Control_OverridePosV", "Control_Acceleration", "Control_Deceleration"}) set(percent, 100);
  int64_t now = 0;
  const auto tick = [&] {
    now += kStepNs;
    drive.step(plant::StepContext{now, kStepNs, bus, world, trace});
  };
  for (int i = 0; i < 100; ++i) tick();
  const TagId jog1 = drive.tag(static_cast<size_t>(drive.portIndex("Control_Jog1")));
  const TagId jog2 = drive.tag(static_cast<size_t>(drive.portIndex("Control_Jog2")));
  const TagId position = drive.tag(static_cast<size_t>(drive.portIndex("Status_ActualPosition")));
  uint64_t i = 0;
  for (auto _ : state) {
    const bool negative = (i++ / 2000) % 2;
    bus.setBool(jog1, negative);
    bus.setBool(jog2, !negative);
    tick();
    benchmark::DoNotOptimize(bus.raw(position));
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));
}

BENCHMARK(BM_DriveTickEpos111);
BENCHMARK(BM_AxisMappingTelegram111);
BENCHMARK(BM_MappedAxisTickEpos111);

}  // namespace
}  // namespace virtcom::bench

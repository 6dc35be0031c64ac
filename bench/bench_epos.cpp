// Per-tick cost of the EPos positioning axis (telegram 111) and of applying a UNIVERSAL_AXIS
// mapping (pack, wire image, drive decode, reply, unpack) — the extra work of a mapped drive.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "cell/yaml_config.hpp"
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

// The mapping layer alone for telegram 111 (the largest image): Control_* values to the words
// the drive decodes, and the reply words back to Status_* values.
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
  drives::RawWords out{}, rx{}, tx{};
  tx[0] = 0x2F37;
  tx[5] = 70000;
  std::array<uint8_t, drives::kMaxImageBytes> image{};
  for (auto _ : state) {
    runtime.pack(values, out);
    runtime.toWire(out, image);
    drives::decode(spec->telegram, drives::Dir::ToDrive, image, rx);
    drives::encode(spec->telegram, drives::Dir::FromDrive, tx, image);
    runtime.fromWire(image, out);
    runtime.unpack(out, values);
    benchmark::DoNotOptimize(rx[0]);
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));
}

BENCHMARK(BM_DriveTickEpos111);
BENCHMARK(BM_AxisMappingTelegram111);

}  // namespace
}  // namespace virtcom::bench

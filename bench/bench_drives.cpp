// Per-tick cost of the drive simulators (issue 5 target: under 100 ns per drive per tick). One
// iteration is one integration step of 1 ms plus one bus cycle (frame in, reply out) — the
// work a drive does per tick when the bus cycle equals the step; a slower bus does less.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <memory>

#include "drives/normalisation.hpp"
#include "drives/powerflex.hpp"
#include "drives/speed_axis.hpp"

namespace virtcom::bench {
namespace {

constexpr int64_t kStepNs = 1'000'000;

template <typename Drive, typename Params>
void runDrive(benchmark::State& state, drives::TelegramId telegram, std::vector<uint32_t> run, const char* type) {
  drives::DriveCommon common;
  common.telegram = telegram;
  std::unique_ptr<Drive> drive;
  if constexpr (std::is_same_v<Drive, drives::SpeedAxis>) drive = std::make_unique<Drive>("D", common, Params{});
  else drive = std::make_unique<Drive>("D", type, common, Params{});
  int64_t now = 0;
  std::vector<uint32_t> off = run;
  off[0] &= ~1u;  // Siemens: ON = 0 first; PowerFlex: no Stop bit change
  drive->exchange(off, now += kStepNs);
  // Warm up into steady running, then measure a ramp-and-run mix: the setpoint flips every
  // 2000 ticks so the ramp, the lag and the status logic all stay busy.
  for (int i = 0; i < 3000; ++i) drive->exchange(run, now += kStepNs);
  std::vector<uint32_t> other = run;
  other[1] = run[1] / 2;
  uint64_t i = 0;
  for (auto _ : state) {
    drive->exchange((i++ / 2000) % 2 ? other : run, now += kStepNs);
    benchmark::DoNotOptimize(drive->tx()[0]);
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));
}

void BM_DriveTickG120Telegram1(benchmark::State& state) {
  runDrive<drives::SpeedAxis, drives::SpeedAxisParams>(state, drives::TelegramId::Std1, {0x047F, 0x2000}, "g120");
}
void BM_DriveTickG120Telegram352(benchmark::State& state) {
  runDrive<drives::SpeedAxis, drives::SpeedAxisParams>(state, drives::TelegramId::Siemens352,
                                                       {0x047F, 0x2000, 0, 0, 0, 0}, "g120");
}
void BM_DriveTickPowerFlex525(benchmark::State& state) {
  runDrive<drives::PowerFlex, drives::PowerFlexParams>(state, drives::TelegramId::Pf525, {0x0012, 1188}, "powerflex525");
}

BENCHMARK(BM_DriveTickG120Telegram1);
BENCHMARK(BM_DriveTickG120Telegram352);
BENCHMARK(BM_DriveTickPowerFlex525);

}  // namespace
}  // namespace virtcom::bench

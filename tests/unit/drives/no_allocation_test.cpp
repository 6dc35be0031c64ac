// The per-tick path of a mapped drive allocates nothing (STYLE rule 7): every example cell in
// examples/drives (PLC scan with UNIVERSAL_AXIS, mapping pack/unpack, wire image, drive decode,
// dynamics, reply) is stepped through acceleration, reversal and stopping with a counted global
// operator new (tests/support/allocation_counter). The trace gets room for its records first;
// the counted window starts after the injected fault, whose report entry is allowed to allocate.
#include <gtest/gtest.h>

#include <filesystem>
#include <ostream>
#include <vector>

#include "cell/cell.hpp"
#include "sim/simulation.hpp"
#include "support/allocation_counter.hpp"

namespace fs = std::filesystem;
using namespace virtcom;

namespace {

constexpr int64_t kMs = 1'000'000;

// The counter itself sees an allocation (so a 0 below means something).
TEST(AllocationCounter, CountsAnAllocation) {
  const test::AllocationCounter allocations;
  std::vector<int> v;
  v.reserve(16);
  EXPECT_EQ(allocations.count(), 1u);
  EXPECT_GE(v.capacity(), 16u);
}

struct Window {
  const char* cell;
  int64_t fromNs, toNs;
};

void PrintTo(const Window& w, std::ostream* os) { *os << w.cell; }

class DriveTickAllocations : public ::testing::TestWithParam<Window> {};

TEST_P(DriveTickAllocations, SteppingTheCellDoesNotAllocate) {
  const Window w = GetParam();
  SourceManager sources;
  Diagnostics diags;
  auto cell = cell::loadCell((fs::path(VIRTCOM_SOURCE_DIR) / "examples" / "drives" / w.cell / "cell.yaml").string(), sources, diags);
  ASSERT_NE(cell, nullptr) << diags.render(sources);
  sim::Simulation sim(*cell, sim::SimOptions{});
  sim.trace().changes.reserve(1 << 22);
  sim.trace().activities.reserve(4096);
  while (sim.nowNs() < w.fromNs) ASSERT_TRUE(sim.step()) << "the run ended early";
  const uint64_t ticksBefore = sim.ticks();
  const test::AllocationCounter allocations;
  while (sim.nowNs() < w.toNs) ASSERT_TRUE(sim.step()) << "the run ended inside the window";
  EXPECT_EQ(allocations.count(), 0u);
  EXPECT_GT(sim.ticks() - ticksBefore, 1000u);
}

// Speed cells: fault at 1.5 s (recovered by 2.5 s), reversal at 3 s, stopping from 5 s; the
// windows end before the run does (its end message allocates). EPos: the positioning sequence.
INSTANTIATE_TEST_SUITE_P(ExampleCells, DriveTickAllocations,
                         ::testing::Values(Window{"g120", 2500 * kMs, 5300 * kMs}, Window{"g120_352", 2500 * kMs, 5300 * kMs},
                                           Window{"pf525", 2500 * kMs, 5300 * kMs}, Window{"pf750", 2500 * kMs, 5300 * kMs},
                                           Window{"epos", 100 * kMs, 3700 * kMs}),
                         [](const auto& info) { return std::string(info.param.cell); });

}  // namespace

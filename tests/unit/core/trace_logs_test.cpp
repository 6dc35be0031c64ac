// The bounded logs of a trace (core/trace_logs.hpp): a short run keeps everything in order, a long
// one its first and last records under stable indices, running activities stay readable, and the
// elided middle adds up to what its records did.
#include <gtest/gtest.h>

#include <vector>

#include "core/trace.hpp"
#include "support/allocation_counter.hpp"

namespace virtcom {
namespace {

constexpr int64_t kMs = 1'000'000;

// A trace with two devices whose activity k (of device k % 2) runs [10k, 10k + 4) ms, ends in
// error when k % 7 == 3 and uses k J.
Trace alternating(size_t window, int count) {
  Trace t;
  t.setWindow(window);
  t.addDevice("A", "press");
  t.addDevice("B", "robot");
  for (int k = 0; k < count; ++k) {
    uint32_t i = t.beginActivity(static_cast<uint32_t>(k % 2), 0, 10 * k * kMs);
    t.endActivity(i, (10 * k + 4) * kMs, k, k % 7 == 3 ? 5 : 0);
  }
  return t;
}

std::vector<size_t> keptIndices(const ActivityLog& log) {
  std::vector<size_t> out;
  for (auto it = log.begin(); it != log.end(); ++it) out.push_back(it.index());
  return out;
}

TEST(TraceLogs, AShortRunKeepsEveryActivityInOrder) {
  Trace t = alternating(100, 100);
  EXPECT_EQ(t.activities.size(), 100u);
  EXPECT_EQ(t.activities.elided(), 0u);
  EXPECT_EQ(t.activities.elidedCount(), 0u);
  EXPECT_TRUE(t.activities.elidedByDevice().empty());
  size_t n = 0;
  for (const ActivityRecord& a : t.activities) {
    EXPECT_EQ(a.startNs, static_cast<int64_t>(10 * n) * kMs);
    ++n;
  }
  EXPECT_EQ(n, 100u);
}

TEST(TraceLogs, ALongRunKeepsItsFirstAndLastHalfUnderTheirIndices) {
  Trace t = alternating(10, 25);
  const ActivityLog& log = t.activities;
  EXPECT_EQ(log.size(), 25u);
  EXPECT_EQ(log.headEnd(), 5u);
  EXPECT_EQ(log.tailBegin(), 20u);
  EXPECT_EQ(log.elided(), 15u);
  EXPECT_EQ(keptIndices(log), (std::vector<size_t>{0, 1, 2, 3, 4, 20, 21, 22, 23, 24}));
  for (size_t i : keptIndices(log)) EXPECT_EQ(log[i].startNs, static_cast<int64_t>(10 * i) * kMs) << i;
  for (size_t i = 5; i < 20; ++i) EXPECT_FALSE(log.held(i)) << i;
  // Backwards as forwards (production reads each device's last activity from the end).
  std::vector<int64_t> starts;
  for (auto it = log.rbegin(); it != log.rend(); ++it) starts.push_back(it->startNs / kMs);
  EXPECT_EQ(starts, (std::vector<int64_t>{240, 230, 220, 210, 200, 40, 30, 20, 10, 0}));
}

TEST(TraceLogs, TheElidedMiddleAddsUpToItsActivities) {
  Trace t = alternating(10, 25);
  const ActivityLog& log = t.activities;
  ASSERT_EQ(log.elidedByDevice().size(), 2u);
  uint32_t count[2] = {}, errors[2] = {};
  double energy[2] = {};
  for (int k = 5; k < 20; ++k) {
    ++count[k % 2];
    errors[k % 2] += k % 7 == 3 ? 1 : 0;
    energy[k % 2] += k;
  }
  for (int d = 0; d < 2; ++d) {
    const ElidedActivities& e = log.elidedByDevice()[d];
    EXPECT_EQ(e.count, count[d]) << d;
    EXPECT_EQ(e.errors, errors[d]) << d;
    EXPECT_EQ(e.energyJ, energy[d]) << d;
    EXPECT_EQ(e.busyNs, 4 * kMs * count[d]) << d;  // disjoint: the union is the sum
  }
  EXPECT_EQ(log.elidedCount(), 15u);
  EXPECT_EQ(log.elidedFromNs(), 50 * kMs);
  EXPECT_EQ(log.elidedToNs(), 194 * kMs);
}

TEST(TraceLogs, OverlappingElidedActivitiesCountTheirUnionOnce) {
  Trace t;
  t.setWindow(2);  // head 1, ring 1: everything between the first and the last is elided
  t.addDevice("A", "press");
  for (int64_t s : {0, 10, 12, 30, 31, 50}) t.endActivity(t.beginActivity(0, 0, s * kMs), (s + 8) * kMs, 0);
  // Elided: [10,18] [12,20] [30,38] [31,39]: union 10 + 9 ms.
  ASSERT_EQ(t.activities.elidedByDevice().size(), 1u);
  EXPECT_EQ(t.activities.elidedByDevice()[0].busyNs, 19 * kMs);
  EXPECT_EQ(t.activities.elidedByDevice()[0].count, 4u);
}

TEST(TraceLogs, ARunningActivityStaysHeldUntilItEndedAndTheRingPassedAgain) {
  Trace t;
  t.setWindow(8);  // head 4, ring 4
  t.addDevice("Belt", "conveyor");
  t.addDevice("Press", "press");
  for (int k = 0; k < 4; ++k) t.endActivity(t.beginActivity(1, 0, k * kMs), k * kMs, 0);
  const uint32_t belt = t.beginActivity(0, 0, 10 * kMs);  // index 4: the first in the ring
  for (int k = 0; k < 2000; ++k) t.endActivity(t.beginActivity(1, 0, (20 + k) * kMs), (20 + k) * kMs, 1);
  ASSERT_FALSE(t.activities.kept(belt));
  ASSERT_TRUE(t.activities.held(belt));
  ASSERT_EQ(t.activities.passed().size(), 1u);
  EXPECT_EQ(t.activities[belt].startNs, 10 * kMs);
  EXPECT_EQ(t.activities[belt].endNs, -1);
  t.endActivity(belt, 5000 * kMs, 7.5);
  EXPECT_EQ(t.activities[belt].endNs, 5000 * kMs);  // its holder reads it back as it ends
  const size_t elidedBefore = t.activities.elidedCount();
  for (int k = 0; k < 3000 && t.activities.held(belt); ++k) t.endActivity(t.beginActivity(1, 0, 6000 * kMs), 6000 * kMs, 0);
  EXPECT_FALSE(t.activities.held(belt));
  EXPECT_TRUE(t.activities.passed().empty());
  const ElidedActivities& e = t.activities.elidedByDevice()[0];
  EXPECT_EQ(e.count, 1u);
  EXPECT_EQ(e.energyJ, 7.5);
  EXPECT_EQ(e.busyNs, 4990 * kMs);
  EXPECT_GT(t.activities.elidedCount(), elidedBefore);
}

TEST(TraceLogs, BeginningActivitiesAllocatesNothingOnceTheWindowIsFull) {
  Trace t;
  t.setWindow(64);
  t.addDevice("A", "press");
  for (int k = 0; k < 200; ++k) t.endActivity(t.beginActivity(0, 0, k * kMs), k * kMs + 1, 0);
  const test::AllocationCounter allocations;
  for (int k = 200; k < 100'000; ++k) t.endActivity(t.beginActivity(0, 0, k * kMs), k * kMs + 1, 0);
  EXPECT_EQ(allocations.count(), 0u);
  EXPECT_EQ(t.activities.size(), 100'000u);
  EXPECT_LE(t.activities.capacity(), 64u);
}

TEST(TraceLogs, CycleStatisticsCoverTheElidedCycles) {
  CycleLog cycles;
  cycles.setLimit(4);
  int64_t start = 0;
  for (int64_t len : {5, 3, 9, 1, 7, 4, 6}) {
    cycles.push_back({start, start + len});
    start += len;
  }
  EXPECT_EQ(cycles.size(), 7u);
  EXPECT_EQ(cycles.elided(), 3u);
  EXPECT_EQ(cycles.minNs(), 1);
  EXPECT_EQ(cycles.maxNs(), 9);
  EXPECT_EQ(cycles.sumNs(), 35.0);
  EXPECT_EQ(cycles.back().endNs - cycles.back().startNs, 6);
  cycles = {{0, 2}, {2, 5}};
  EXPECT_EQ(cycles.size(), 2u);
  EXPECT_EQ(cycles.minNs(), 2);
  EXPECT_EQ(cycles.maxNs(), 3);
}

}  // namespace
}  // namespace virtcom

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "core/clock.hpp"

namespace virtcom {
namespace {

TEST(VirtualClock, StartsAtZero) {
  VirtualClock clock;
  EXPECT_EQ(clock.nowNs(), 0);
}

TEST(VirtualClock, JumpsToTheTarget) {
  VirtualClock clock;
  clock.advanceTo(10'000'000);
  EXPECT_EQ(clock.nowNs(), 10'000'000);
  clock.advanceTo(int64_t{365} * 86'400'000'000'000);  // a year of virtual time costs nothing
  EXPECT_EQ(clock.nowNs(), int64_t{365} * 86'400'000'000'000);
}

TEST(VirtualClock, NeverGoesBackwards) {
  VirtualClock clock;
  clock.advanceTo(500);
  clock.advanceTo(499);
  EXPECT_EQ(clock.nowNs(), 500);
  clock.advanceTo(-1);
  EXPECT_EQ(clock.nowNs(), 500);
  clock.advanceTo(500);
  EXPECT_EQ(clock.nowNs(), 500);
  clock.advanceTo(501);
  EXPECT_EQ(clock.nowNs(), 501);
}

TEST(VirtualClock, UsableThroughTheClockInterface) {
  VirtualClock virt;
  Clock& clock = virt;
  clock.advanceTo(42);
  EXPECT_EQ(clock.nowNs(), 42);
}

// The paced clock sleeps by design; at a speed of 1e9 a whole microsecond of virtual time is
// one wall nanosecond, so this stays instant. No timing is asserted, only the virtual time.
TEST(PacedClock, ReportsVirtualTimeAndNeverGoesBackwards) {
  PacedClock clock(1e9);
  EXPECT_EQ(clock.nowNs(), 0);
  clock.advanceTo(1000);
  EXPECT_EQ(clock.nowNs(), 1000);
  clock.advanceTo(10);
  EXPECT_EQ(clock.nowNs(), 1000);
}

// The live HMI changes the pace while a run goes and pauses it: virtual time carries on from
// where it was, and a speed that is not positive is ignored.
TEST(PacedClock, SpeedChangesAndResumeKeepVirtualTime) {
  PacedClock clock(1e9);
  clock.advanceTo(1000);
  clock.setSpeed(2e9);
  EXPECT_EQ(clock.speed(), 2e9);
  clock.setSpeed(0);
  clock.setSpeed(-1);
  EXPECT_EQ(clock.speed(), 2e9);
  EXPECT_EQ(clock.nowNs(), 1000);
  clock.resume();
  clock.advanceTo(3000);
  EXPECT_EQ(clock.nowNs(), 3000);
}

TEST(MonotonicNow, DoesNotDecrease) {
  int64_t a = monotonicNowNs();
  int64_t b = monotonicNowNs();
  EXPECT_LE(a, b);
}

// A tick is late when the wall clock is already past its due time when it is reached (the work
// since the previous one overran the period); a tick reached early sleeps and is on time. The
// periods are long (100 ms) so a busy test machine does not make the on-time ticks late.
TEST(PacedClock, CountsTheTicksThatStartLate) {
  PacedClock clock(1.0);
  clock.advanceTo(100'000'000);  // sleeps about 100 ms: on time
  EXPECT_EQ(clock.lateTicks(), 0u);
  std::this_thread::sleep_for(std::chrono::milliseconds(250));  // the next tick's work overruns
  clock.advanceTo(200'000'000);
  EXPECT_EQ(clock.lateTicks(), 1u);
  EXPECT_GE(clock.maxLateNs(), 150'000'000);
  clock.advanceTo(300'000'000);  // 250 + 100 ms past the anchor: still behind
  EXPECT_EQ(clock.lateTicks(), 2u);
  clock.resume();  // a pause's end: lateness before it is forgotten
  clock.advanceTo(400'000'000);
  EXPECT_EQ(clock.lateTicks(), 2u);
}

}  // namespace
}  // namespace virtcom

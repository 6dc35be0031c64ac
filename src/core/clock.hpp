#pragma once
// The one place that knows what time it is. Everything else receives a Clock, so the same code
// runs in virtual time (as fast as possible, deterministic) or paced to the wall clock.
#include <cstdint>

namespace virtcom {

class Clock {
 public:
  virtual ~Clock() = default;
  // Current time in ns since the start of the run.
  virtual int64_t nowNs() const = 0;
  // Advances to `targetNs`: a virtual clock jumps, a paced clock sleeps until the wall clock
  // (scaled by its speed factor) reaches it. Never goes backwards.
  virtual void advanceTo(int64_t targetNs) = 0;
};

// Monotonic wall time in ns, for measuring how long work took (statistics only: never used to
// decide what a simulation does).
int64_t monotonicNowNs();
// UTC wall time in ns since 1970-01-01, for timestamps shown to the outside world (ADS
// notification stamps); never used to decide what a simulation does.
int64_t utcNowNs();

class VirtualClock final : public Clock {
 public:
  int64_t nowNs() const override { return nowNs_; }
  void advanceTo(int64_t targetNs) override {
    if (targetNs > nowNs_) nowNs_ = targetNs;
  }

 private:
  int64_t nowNs_ = 0;
};

// Virtual time that follows the wall clock at `speed` (1.0 = real time, 2.0 = twice as fast).
// Pacing is measured from an anchor (wall time, virtual time) that setSpeed() and resume() move
// to the present, so a changed speed or a pause (a live HMI) never makes the clock catch up.
class PacedClock final : public Clock {
 public:
  explicit PacedClock(double speed);
  int64_t nowNs() const override { return nowNs_; }
  void advanceTo(int64_t targetNs) override;
  double speed() const { return speed_; }
  // From now on, follow the wall clock at `speed` (> 0; other values are ignored).
  void setSpeed(double speed);
  // After a pause: the time spent paused does not count.
  void resume();
  // advanceTo() calls that found the wall clock already past the target (the work since the
  // previous one overran it: a late tick), and by how much at most. Counting allocates nothing.
  uint64_t lateTicks() const { return lateTicks_; }
  int64_t maxLateNs() const { return maxLateNs_; }

 private:
  double speed_;
  int64_t anchorWallNs_;
  int64_t anchorVirtualNs_ = 0;
  int64_t nowNs_ = 0;
  uint64_t lateTicks_ = 0;
  int64_t maxLateNs_ = 0;
};

}  // namespace virtcom

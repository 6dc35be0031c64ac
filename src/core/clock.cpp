#include "core/clock.hpp"

#include <algorithm>
#include <chrono>
#include <thread>

namespace virtcom {

static int64_t wallNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

int64_t monotonicNowNs() { return wallNs(); }

int64_t utcNowNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
}

PacedClock::PacedClock(double speed) : speed_(speed > 0 ? speed : 1.0), anchorWallNs_(wallNs()) {}

void PacedClock::setSpeed(double speed) {
  if (!(speed > 0)) return;
  speed_ = speed;
  resume();
}

void PacedClock::resume() {
  anchorWallNs_ = wallNs();
  anchorVirtualNs_ = nowNs_;
}

void PacedClock::advanceTo(int64_t targetNs) {
  if (targetNs <= nowNs_) return;
  int64_t wallTarget = anchorWallNs_ + static_cast<int64_t>(static_cast<double>(targetNs - anchorVirtualNs_) / speed_);
  int64_t remaining = wallTarget - wallNs();
  if (remaining > 0) {
    std::this_thread::sleep_for(std::chrono::nanoseconds(remaining));
  } else {
    ++lateTicks_;
    maxLateNs_ = std::max(maxLateNs_, -remaining);
  }
  nowNs_ = targetNs;
}

}  // namespace virtcom

#pragma once
// Test-only: waiting on another thread or process without timing assertions. A condition is
// polled until it holds or a generous deadline passes, so slow (sanitizer) builds still pass
// and a bug fails the test instead of hanging it.
#include <chrono>
#include <thread>

namespace virtcom::test {

inline constexpr auto kDeadline = std::chrono::seconds(20);

// Polls `condition` every few milliseconds; true once it holds, false after `deadline`.
template <class Condition>
bool eventually(Condition&& condition, std::chrono::milliseconds deadline = kDeadline) {
  const auto until = std::chrono::steady_clock::now() + deadline;
  while (std::chrono::steady_clock::now() < until) {
    if (condition()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return false;
}

}  // namespace virtcom::test

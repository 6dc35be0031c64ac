#pragma once
// C++ twins of the standard function blocks the benchmarks use, statement for statement the
// same as src/lang/st/prelude.cpp (TIME in ms as int32, the task time in ns), so a native
// twin does the same work as the ST program and produces bit-identical results.
#include <cstdint>

namespace virtcom::bench {

struct NativeTon {
  bool in = false;
  int32_t ptMs = 0;
  bool q = false;
  int32_t etMs = 0;
  int64_t startNs = 0;
  bool running = false;

  void call(int64_t nowNs) {
    if (in) {
      if (!running) {
        running = true;
        startNs = nowNs;
      }
      const auto elapsedMs = static_cast<int32_t>((nowNs - startNs) / 1'000'000);
      if (elapsedMs >= ptMs) {
        q = true;
        etMs = ptMs;
      } else {
        q = false;
        etMs = elapsedMs;
      }
    } else {
      running = false;
      q = false;
      etMs = 0;
    }
  }
};

struct NativeCtu {
  bool cu = false;
  bool reset = false;
  int16_t pv = 0;
  bool q = false;
  int16_t cv = 0;
  bool prevCu = false;

  void call() {
    if (reset) cv = 0;
    else if (cu && !prevCu && cv < 32767) cv = static_cast<int16_t>(cv + 1);
    q = cv >= pv;
    prevCu = cu;
  }
};

struct NativeRTrig {
  bool clk = false;
  bool q = false;
  bool m = false;

  void call() {
    q = clk && !m;
    m = clk;
  }
};

}  // namespace virtcom::bench

#pragma once
// Key performance indicators of one run, computed from its Trace alone. Every report (summary
// table, JSON, HTML) prints these numbers, so they are computed once, here.
#include <cstdint>
#include <string>
#include <vector>

#include "core/trace.hpp"

namespace virtcom::report {

// Per-device figures. Times are clipped to the measured window (Kpis::windowStartNs..EndNs).
struct DeviceKpis {
  uint32_t device = 0;          // index into Trace::devices
  int64_t busyNs = 0;           // union of the device's activities inside the window
  int64_t idleNs = 0;           // window length - busyNs
  double utilisationPct = 0;    // busyNs / window length * 100; 0 for an empty window
  double energyJ = 0;           // Trace::totals: the whole run, idle consumption included
  double activityEnergyJ = 0;   // sum of energyJ of the activities counted in `operations`
  uint32_t operations = 0;      // activities overlapping the window (a 0-length one inside it counts)
  uint32_t errors = 0;          // activities with a non-zero error code, anywhere in the run
  uint32_t running = 0;         // activities still running when the run ended (endNs == -1)
};

struct Kpis {
  // The measured window: the cycle markers when the run has them (cycleEndNs > cycleStartNs),
  // otherwise the whole run [0, endNs].
  bool cycleMeasured = false;
  int64_t windowStartNs = 0;
  int64_t windowEndNs = 0;
  int64_t cycleTimeNs = 0;      // windowEndNs - windowStartNs
  uint32_t cyclesCompleted = 0;
  // The lengths of every cycle of Trace::cycles (0 without any); the cycle time above is the last.
  int64_t cycleMinNs = 0, cycleMaxNs = 0;
  double cycleMeanNs = 0;
  int64_t runNs = 0;            // Trace::endNs

  std::vector<DeviceKpis> devices;  // one per Trace::devices, same order
  double totalEnergyJ = 0;          // sum of DeviceKpis::energyJ
  uint32_t operations = 0;          // sums over devices
  uint32_t errors = 0;
  uint32_t collisions = 0;          // whole run
  uint32_t faults = 0;              // whole run

  RunEnd end = RunEnd::Completed;
  std::string endMessage;
};

// Computes the KPIs. Pure and deterministic; tolerates inconsistent traces (out-of-range device
// indices are skipped, activities still running end at Trace::endNs, totals missing for a
// device read as 0). Allocates; O(activities log activities) over the activities the trace keeps
// (a long run's elided middle counts through its aggregates: docs/report.md "Long runs").
Kpis computeKpis(const Trace& trace);

}  // namespace virtcom::report

#pragma once
// What a watched plant produced against its plan (docs/monitor.md, "Planned vs actual"): parts
// (completed cycles) per occurrence of a planned shift and per day, the plan pro-rated to the
// part of each shift that was watched; and each station's elapsed time in its current
// operation. Times of day are local wall-clock time, given by the caller (an injected clock).
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "core/production_plan.hpp"
#include "core/trace.hpp"

namespace virtcom::report {

inline constexpr int64_t kDayNs = 86'400'000'000'000;

// One occurrence of a planned shift (a day's Early shift), as watched.
struct ShiftCount {
  uint32_t shift = 0;         // index into ProductionPlan::shifts
  int64_t startNs = 0;        // local wall time: ns since 1970-01-01 00:00 local time
  int64_t endNs = 0;
  int64_t watchedFromNs = 0;  // the start, unless the watch began in the middle of the shift
  uint32_t actual = 0;        // cycles completed in it
};

// Counts completed cycles into the shift occurrence the wall clock is in. update() runs every
// poll: one comparison and an addition, unless a shift begins or ends (then a search of the
// plan and, once a shift, an append).
class ProductionCounter {
 public:
  explicit ProductionCounter(const ProductionPlan& plan);
  // `localNs`: the local wall time now; `cyclesCompleted`: the count so far (never decreases).
  void update(int64_t localNs, uint32_t cyclesCompleted);
  const ProductionPlan& plan() const { return plan_; }
  const std::vector<ShiftCount>& shifts() const { return shifts_; }  // every occurrence watched, in time order
  // The occurrence the clock was in at the last update(); null between shifts or before it.
  const ShiftCount* current() const { return inShift_ ? &shifts_.back() : nullptr; }
  int64_t lastNs() const { return lastNs_; }  // the local wall time of the last update()

 private:
  void enter(int64_t localNs);

  const ProductionPlan& plan_;
  std::vector<ShiftCount> shifts_;
  int64_t boundaryNs_ = std::numeric_limits<int64_t>::min();  // the current shift's end, or the next one's start
  bool inShift_ = false;
  bool started_ = false;
  uint32_t cycles_ = 0;
  int64_t lastNs_ = 0;
};

// The shift's plan pro-rated to the watched part of `count` up to `localNs`: parts × watched / length.
double planNow(const PlannedShift& shift, const ShiftCount& count, int64_t localNs);

// The monitor's figures at one moment, for the summary, the JSON report and the historian.
struct ProductionReport {
  struct Shift {
    std::string day;            // "2026-12-02": the local date the shift started on
    std::string name;
    int64_t startNs = 0, endNs = 0, watchedFromNs = 0;  // local wall time
    uint32_t plan = 0;          // the whole shift's planned parts
    double planNow = 0;         // the plan pro-rated to the watched part up to now: plan × watched / length
    uint32_t actual = 0;
  };
  struct Day {
    std::string day;
    uint32_t plan = 0;          // the shifts of that day that were watched
    double planNow = 0;
    uint32_t actual = 0;
  };
  struct Station {
    uint32_t device = 0;
    std::string name;
    std::string operation;      // empty: idle
    int64_t elapsedNs = 0;      // in the current operation (0 when idle)
  };
  std::vector<Shift> shifts;
  std::vector<Day> days;
  std::vector<Station> stations;  // one per device of the trace
};

// The figures at local wall time `localNs` (run time `nowNs` for the stations). Allocates.
ProductionReport productionReport(const ProductionCounter& counter, int64_t localNs, const Trace& trace, int64_t nowNs);
// "2026-12-02" for a local wall time.
std::string localDate(int64_t localNs);
// The tables the monitor prints when stopped: shifts and days (if planned), stations.
std::string productionTable(const ProductionReport& r);

}  // namespace virtcom::report

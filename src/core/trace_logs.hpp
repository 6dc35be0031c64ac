#pragma once
// The two parts of a Trace that grow with the number of operations and cycles, bounded by
// HeadTailLog (core/head_tail_log.hpp): a long run keeps the first and the last records for the
// Gantt chart and the cycle tables, and what the reports need of the elided middle as
// aggregates (docs/report.md "Long runs").
#include <cstdint>
#include <vector>

#include "core/head_tail_log.hpp"

namespace virtcom {

struct ActivityRecord {
  uint32_t device = 0;
  uint32_t label = 0;     // index into Trace::labels
  int64_t startNs = 0;
  int64_t endNs = -1;     // -1 while running
  double energyJ = 0;
  int32_t errorCode = 0;  // non-zero: the activity ended in this error
};

// One completed cycle: from the end of the one before (the start of the run for the first, so it
// includes the start-up) to the rising edge of the cycle marker.
struct CycleRecord {
  int64_t startNs = 0;
  int64_t endNs = 0;
};

// What the elided activities of one device add up to (all ended).
struct ElidedActivities {
  uint32_t count = 0;
  uint32_t errors = 0;        // with a non-zero error code
  double energyJ = 0;
  int64_t busyNs = 0;         // the union of their intervals
  int64_t coveredUntilNs = 0; // end of that union so far (they are elided in start order)
};

// Activities in start order, indexed by the number beginActivity hands out. An activity still
// running when the ring passes it is not elided: it stays held (operator[] finds it) until it
// ended and at least as many activities as the ring holds have begun since, so every holder of
// an index (a device, a sink that keeps its own position) reads it back as it ends.
// Contract: operator[](i) requires held(i). push_back allocates only during warm-up (and when a
// running activity is first passed by the ring, or a new device index is first elided).
class ActivityLog : public HeadTailLog<ActivityRecord> {
 public:
  using Base = HeadTailLog<ActivityRecord>;
  ActivityLog() = default;
  ActivityLog(std::initializer_list<ActivityRecord> records) {
    for (const ActivityRecord& a : records) push_back(a);
  }

  // Appends; returns the new activity's index.
  uint32_t push_back(const ActivityRecord& a);
  bool held(size_t i) const { return Base::kept(i) || findPassed(i) != nullptr; }
  const ActivityRecord& operator[](size_t i) const;
  ActivityRecord& operator[](size_t i);
  void clear();

  // Running activities the ring has passed (they are not among begin()..end()), in index order.
  struct Passed {
    uint32_t index = 0;
    ActivityRecord record;
    size_t endedAt = 0;  // size() when first seen ended; 0 while running
  };
  const std::vector<Passed>& passed() const { return passed_; }
  // Per device index, what the elided activities add up to; empty while nothing was elided.
  const std::vector<ElidedActivities>& elidedByDevice() const { return elidedByDevice_; }
  // The elided activities' span: the first one's start and the latest end (0, 0 without any).
  int64_t elidedFromNs() const { return elidedFromNs_; }
  int64_t elidedToNs() const { return elidedToNs_; }
  // How many activities were elided in all (Base::elided() less those still held as passed).
  size_t elidedCount() const { return elidedCount_; }

 private:
  const Passed* findPassed(size_t i) const;
  void elide(const ActivityRecord& a);
  void releaseEndedPassed();

  std::vector<Passed> passed_;
  std::vector<ElidedActivities> elidedByDevice_;
  int64_t elidedFromNs_ = 0, elidedToNs_ = 0;
  size_t elidedCount_ = 0;
};

// Completed cycles in order, with the length statistics of all of them (elided included).
class CycleLog : public HeadTailLog<CycleRecord> {
 public:
  using Base = HeadTailLog<CycleRecord>;
  CycleLog() = default;
  CycleLog(std::initializer_list<CycleRecord> records) { *this = records; }
  CycleLog& operator=(std::initializer_list<CycleRecord> records);

  void push_back(const CycleRecord& c);
  void clear();
  // Over every cycle appended (0 without any); the sum in append order.
  int64_t minNs() const { return minNs_; }
  int64_t maxNs() const { return maxNs_; }
  double sumNs() const { return sumNs_; }

 private:
  int64_t minNs_ = 0, maxNs_ = 0;
  double sumNs_ = 0;
};

}  // namespace virtcom

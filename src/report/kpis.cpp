#include "report/kpis.hpp"

#include <algorithm>
#include <utility>

#include "report/text_util.hpp"

namespace virtcom::report {

namespace {

using Interval = std::pair<int64_t, int64_t>;

// Total length of the union of intervals (sorted in place).
int64_t unionLength(std::vector<Interval>& intervals) {
  std::sort(intervals.begin(), intervals.end());
  int64_t total = 0;
  int64_t curStart = 0, curEnd = 0;
  bool open = false;
  for (const auto& [s, e] : intervals) {
    if (open && s <= curEnd) {
      curEnd = std::max(curEnd, e);
      continue;
    }
    if (open) total += curEnd - curStart;
    curStart = s;
    curEnd = e;
    open = true;
  }
  if (open) total += curEnd - curStart;
  return total;
}

// A long run's elided activities (all ended, all before the kept last ones) count in full when
// the window is the whole run; against a measured cycle only their errors count, as the window
// is the last cycle, which the kept tail covers. Their busy time is their own union, added to the
// kept ones' (they overlap at most at the two edges of the elided span).
void addElided(DeviceKpis& d, const ElidedActivities& e, const Kpis& k) {
  d.errors += e.errors;
  if (k.cycleMeasured) return;
  d.operations += e.count;
  d.activityEnergyJ += e.energyJ;
  d.busyNs = std::min(d.busyNs + e.busyNs, k.cycleTimeNs);
}

}  // namespace

Kpis computeKpis(const Trace& trace) {
  Kpis k;
  k.runNs = trace.endNs;
  k.cyclesCompleted = trace.cyclesCompleted;
  k.cycleMeasured = trace.cycleEndNs > trace.cycleStartNs;
  k.windowStartNs = k.cycleMeasured ? trace.cycleStartNs : 0;
  k.windowEndNs = k.cycleMeasured ? trace.cycleEndNs : std::max<int64_t>(trace.endNs, 0);
  k.cycleTimeNs = k.windowEndNs - k.windowStartNs;
  if (!trace.cycles.empty()) {
    k.cycleMinNs = trace.cycles.minNs();
    k.cycleMaxNs = trace.cycles.maxNs();
    k.cycleMeanNs = trace.cycles.sumNs() / static_cast<double>(trace.cycles.size());
  }
  k.collisions = static_cast<uint32_t>(trace.collisions.size());
  k.faults = static_cast<uint32_t>(trace.faults.size());
  k.end = trace.end;
  k.endMessage = trace.endMessage;

  const size_t n = trace.devices.size();
  k.devices.resize(n);
  std::vector<std::vector<Interval>> busy(n);
  for (uint32_t index : heldActivities(trace)) {
    const ActivityRecord& a = trace.activities[index];
    if (a.device >= n) continue;
    DeviceKpis& d = k.devices[a.device];
    if (a.errorCode != 0) ++d.errors;
    if (a.endNs < 0) ++d.running;
    int64_t start = a.startNs, end = activityEndNs(trace, a);
    bool overlaps = start == end ? start >= k.windowStartNs && start <= k.windowEndNs
                                 : start < k.windowEndNs && end > k.windowStartNs;
    if (!overlaps) continue;
    ++d.operations;
    d.activityEnergyJ += a.energyJ;
    int64_t s = std::max(start, k.windowStartNs), e = std::min(end, k.windowEndNs);
    if (e > s) busy[a.device].emplace_back(s, e);
  }
  const std::vector<ElidedActivities>& elided = trace.activities.elidedByDevice();
  for (uint32_t i = 0; i < n; ++i) {
    DeviceKpis& d = k.devices[i];
    d.device = i;
    d.busyNs = unionLength(busy[i]);
    if (i < elided.size()) addElided(d, elided[i], k);
    d.idleNs = k.cycleTimeNs - d.busyNs;
    d.utilisationPct = k.cycleTimeNs > 0 ? 100.0 * static_cast<double>(d.busyNs) /
                                               static_cast<double>(k.cycleTimeNs)
                                         : 0.0;
    d.energyJ = i < trace.totals.size() ? trace.totals[i].energyJ : 0.0;
    k.totalEnergyJ += d.energyJ;
    k.operations += d.operations;
    k.errors += d.errors;
  }
  return k;
}

}  // namespace virtcom::report

#include "report/production.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "report/text_util.hpp"

namespace virtcom::report {

namespace {

constexpr int64_t kMinuteNs = 60'000'000'000;

int64_t floorDiv(int64_t a, int64_t b) { return a / b - (a % b != 0 && (a < 0) != (b < 0)); }

int64_t lengthNs(const PlannedShift& s) {
  int32_t min = s.endMin > s.startMin ? s.endMin - s.startMin : s.endMin + 24 * 60 - s.startMin;
  return min * kMinuteNs;
}

}  // namespace

ProductionCounter::ProductionCounter(const ProductionPlan& plan) : plan_(plan) {
  shifts_.reserve(64);  // three weeks of three shifts before the first reallocation
}

void ProductionCounter::update(int64_t localNs, uint32_t cyclesCompleted) {
  if (localNs >= boundaryNs_) enter(localNs);
  if (inShift_) shifts_.back().actual += cyclesCompleted - cycles_;
  cycles_ = cyclesCompleted;
  lastNs_ = localNs;
}

// The shift occurrence holding `localNs` (one starting today or, a night shift, yesterday), or
// else the wait until the next one starts.
void ProductionCounter::enter(int64_t localNs) {
  const int64_t midnight = floorDiv(localNs, kDayNs) * kDayNs;
  inShift_ = false;
  boundaryNs_ = std::numeric_limits<int64_t>::max();
  for (uint32_t i = 0; i < plan_.shifts.size(); ++i) {
    const PlannedShift& s = plan_.shifts[i];
    for (int64_t day : {-1, 0, 1}) {
      const int64_t start = midnight + day * kDayNs + s.startMin * kMinuteNs, end = start + lengthNs(s);
      if (start <= localNs && localNs < end) {
        shifts_.push_back({i, start, end, started_ ? start : localNs, 0});
        inShift_ = true;
        boundaryNs_ = end;
        started_ = true;
        return;
      }
      if (start > localNs) boundaryNs_ = std::min(boundaryNs_, start);
    }
  }
  started_ = true;
}

std::string localDate(int64_t localNs) {
  const std::chrono::sys_days days{std::chrono::days{floorDiv(localNs, kDayNs)}};
  const std::chrono::year_month_day ymd{days};
  char text[16];
  std::snprintf(text, sizeof text, "%04d-%02u-%02u", static_cast<int>(ymd.year()), static_cast<unsigned>(ymd.month()),
                static_cast<unsigned>(ymd.day()));
  return text;
}

double planNow(const PlannedShift& shift, const ShiftCount& count, int64_t localNs) {
  const int64_t watched = std::clamp(localNs, count.watchedFromNs, count.endNs) - count.watchedFromNs;
  return static_cast<double>(shift.parts) * static_cast<double>(watched) / static_cast<double>(count.endNs - count.startNs);
}

ProductionReport productionReport(const ProductionCounter& counter, int64_t localNs, const Trace& trace, int64_t nowNs) {
  ProductionReport r;
  for (const ShiftCount& c : counter.shifts()) {
    const PlannedShift& s = counter.plan().shifts[c.shift];
    r.shifts.push_back({localDate(c.startNs), s.name, c.startNs, c.endNs, c.watchedFromNs, s.parts, planNow(s, c, localNs), c.actual});
    const ProductionReport::Shift& row = r.shifts.back();
    if (r.days.empty() || r.days.back().day != row.day) r.days.push_back({row.day, 0, 0, 0});
    r.days.back().plan += row.plan;
    r.days.back().planNow += row.planNow;
    r.days.back().actual += row.actual;
  }
  r.stations.resize(trace.devices.size());
  for (uint32_t d = 0; d < r.stations.size(); ++d) {
    r.stations[d].device = d;
    r.stations[d].name = trace.devices[d].name;
  }
  // Activities are in start order: each device's last one is its current one, if still running.
  std::vector<bool> seen(trace.devices.size(), false);
  const std::vector<uint32_t> held = heldActivities(trace);
  for (auto i = held.rbegin(); i != held.rend(); ++i) {
    const ActivityRecord* a = &trace.activities[*i];
    if (a->device >= seen.size() || seen[a->device]) continue;
    seen[a->device] = true;
    if (a->endNs >= 0) continue;
    r.stations[a->device].operation = labelName(trace, a->label);
    r.stations[a->device].elapsedNs = std::max<int64_t>(0, nowNs - a->startNs);
  }
  return r;
}

std::string productionTable(const ProductionReport& r) {
  std::string out;
  char line[256];
  if (!r.shifts.empty()) {
    std::snprintf(line, sizeof line, "\n%-10s %-12s %8s %8s %8s %8s\n", "Day", "Shift", "Plan", "Plan now", "Actual", "Actual%");
    out += line;
    auto row = [&](const std::string& day, const std::string& name, uint32_t plan, double planNow, uint32_t actual) {
      std::string pct = planNow > 0 ? formatFixed(100.0 * actual / planNow, 1) : "-";
      std::snprintf(line, sizeof line, "%-10s %-12s %8u %8s %8u %8s\n", day.c_str(), fitWidth(name, 12).c_str(), plan,
                    formatFixed(planNow, 1).c_str(), actual, pct.c_str());
      out += line;
    };
    for (const auto& s : r.shifts) row(s.day, s.name, s.plan, s.planNow, s.actual);
    for (const auto& d : r.days) row(d.day, "(day)", d.plan, d.planNow, d.actual);
  }
  std::snprintf(line, sizeof line, "\n%-12s %-16s %10s\n", "Station", "Operation", "Elapsed s");
  out += line;
  for (const auto& s : r.stations) {
    std::snprintf(line, sizeof line, "%-12s %-16s %10s\n", fitWidth(s.name, 12).c_str(), s.operation.empty() ? "(idle)" : fitWidth(s.operation, 16).c_str(),
                  s.operation.empty() ? "-" : formatSeconds(s.elapsedNs, 3).c_str());
    out += line;
  }
  return out;
}

}  // namespace virtcom::report

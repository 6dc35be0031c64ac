#include "core/trace_logs.hpp"

#include <algorithm>

namespace virtcom {

namespace {

// Passed running activities are released at most once per this many appends: the check walks
// them all, and they are as many as the activities running at once.
constexpr size_t kReleaseEvery = 1024;

}  // namespace

uint32_t ActivityLog::push_back(const ActivityRecord& a) {
  const size_t index = size();
  if (const ActivityRecord* out = Base::push_back(a)) {
    const size_t outIndex = index - tailCapacity();
    if (out->endNs < 0) passed_.push_back({static_cast<uint32_t>(outIndex), *out, 0});
    else elide(*out);
  }
  if (!passed_.empty() && size() % kReleaseEvery == 0) releaseEndedPassed();
  return static_cast<uint32_t>(index);
}

const ActivityLog::Passed* ActivityLog::findPassed(size_t i) const {
  auto it = std::ranges::lower_bound(passed_, i, {}, &Passed::index);
  return it != passed_.end() && it->index == i ? &*it : nullptr;
}

const ActivityRecord& ActivityLog::operator[](size_t i) const {
  if (Base::kept(i)) return Base::operator[](i);
  const Passed* p = findPassed(i);
  assert(p);
  return p->record;
}

ActivityRecord& ActivityLog::operator[](size_t i) {
  return const_cast<ActivityRecord&>(static_cast<const ActivityLog&>(*this)[i]);
}

void ActivityLog::clear() {
  Base::clear();
  passed_.clear();
  elidedByDevice_.clear();
  elidedFromNs_ = elidedToNs_ = 0;
  elidedCount_ = 0;
}

// Activities are elided in start order (a passed one later, when released), so each device's
// busy union grows at its end: only the part of [start, end] past what it covers so far is new.
void ActivityLog::elide(const ActivityRecord& a) {
  if (a.device >= elidedByDevice_.size()) elidedByDevice_.resize(a.device + 1);
  ElidedActivities& e = elidedByDevice_[a.device];
  if (e.count == 0) e.coveredUntilNs = a.startNs;
  ++e.count;
  if (a.errorCode != 0) ++e.errors;
  e.energyJ += a.energyJ;
  const int64_t from = std::max(a.startNs, e.coveredUntilNs);
  if (a.endNs > from) e.busyNs += a.endNs - from;
  e.coveredUntilNs = std::max(e.coveredUntilNs, a.endNs);
  elidedFromNs_ = elidedCount_ == 0 ? a.startNs : std::min(elidedFromNs_, a.startNs);
  elidedToNs_ = std::max(elidedToNs_, a.endNs);
  ++elidedCount_;
}

// A passed activity that ended stays readable while as many activities begin as the ring holds,
// as it would have in the ring; then it joins the elided aggregates.
void ActivityLog::releaseEndedPassed() {
  std::erase_if(passed_, [&](Passed& p) {
    if (p.record.endNs < 0) return false;
    if (p.endedAt == 0) p.endedAt = size();
    if (size() - p.endedAt < tailCapacity()) return false;
    elide(p.record);
    return true;
  });
}

CycleLog& CycleLog::operator=(std::initializer_list<CycleRecord> records) {
  clear();
  for (const CycleRecord& c : records) push_back(c);
  return *this;
}

void CycleLog::push_back(const CycleRecord& c) {
  const int64_t ns = c.endNs - c.startNs;
  minNs_ = empty() ? ns : std::min(minNs_, ns);
  maxNs_ = empty() ? ns : std::max(maxNs_, ns);
  sumNs_ += static_cast<double>(ns);
  Base::push_back(c);
}

void CycleLog::clear() {
  Base::clear();
  minNs_ = maxNs_ = 0;
  sumNs_ = 0;
}

}  // namespace virtcom

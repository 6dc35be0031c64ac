#include "history/recorder.hpp"

#include <algorithm>
#include <cstring>

#include "core/clock.hpp"
#include "history/schema.hpp"

namespace virtcom::history {

namespace {

// The writer looks at the queue this often; it commits when the flush period has passed or the
// queue is a quarter full, whichever comes first.
constexpr int64_t kPollNs = 10'000'000;
constexpr int64_t kRetentionPeriodNs = 60'000'000'000;

}  // namespace

std::expected<std::unique_ptr<Recorder>, std::string> Recorder::open(const std::string& path, RecorderOptions options) {
  auto db = openDatabase(path, OpenMode::Record);
  if (!db) return std::unexpected(db.error());
  std::unique_ptr<Recorder> recorder(new Recorder(std::move(*db), std::move(options)));
  if (recorder->options_.retention.any()) {
    int64_t pruned = pruneRuns(recorder->db_, recorder->options_.retention, 0, utcNowNs());
    if (pruned < 0) return std::unexpected(path + ": cannot apply the retention limits (" + recorder->db_.errorText() + ")");
    recorder->pruned_ = pruned;
  }
  return recorder;
}

Recorder::Recorder(Connection db, RecorderOptions options)
    : db_(std::move(db)), options_(std::move(options)), writer_(db_), queue_(options_.queueEvents) {}

Recorder::~Recorder() { stopWriter(); }

void Recorder::begin(const Trace& trace) {
  run_ = writer_.writeStart(trace, {options_.cellName, options_.cellFile, utcNowNs(), options_.timeline, options_.shiftNames});
  if (run_ < 0) {
    error_ = writer_.error();
    return;  // every event then counts as dropped: nothing takes them off the queue
  }
  openActivities_.reserve(std::max<size_t>(64, trace.devices.size() * 4));
  thread_ = std::thread([this] { writerLoop(); });
}

template <class Fill>
void Recorder::push(size_t n, bool wait, Fill&& fill) {
  wait = wait || options_.waitWhenFull;
  while (!queue_.tryPush(n, fill)) {
    // Waiting only helps with a writer to make room, and room enough for n.
    if (!wait || !thread_.joinable() || n > queue_.capacity()) {
      drops_.fetch_add(1, std::memory_order_relaxed);
      return;
    }
    // Only a run that may wait gets here: wake the writer now rather than at its next poll.
    if (!hurry_.exchange(true, std::memory_order_relaxed)) wake_.notify_one();
    std::this_thread::yield();
  }
}

void Recorder::change(const SignalChange& c) {
  push(1, false, [&c](Event& e, size_t) {
    e.kind = EventKind::Change;
    e.index = c.tag;
    e.timeNs = c.timeNs;
    e.raw = c.raw;
  });
}

void Recorder::pushActivity(const Trace& trace, uint32_t index, bool wait) {
  const ActivityRecord& a = trace.activities[index];
  push(1, wait, [&](Event& e, size_t) {
    e.kind = EventKind::Activity;
    e.index = index;
    e.timeNs = a.startNs;
    e.activity = {a.device, a.label, a.startNs, a.endNs, a.energyJ, a.errorCode};
  });
}

template <class Head>
void Recorder::pushWithTexts(std::span<const std::string_view> texts, bool wait, Head&& head) {
  size_t bytes = 0;
  for (std::string_view t : texts) bytes += t.size();
  push(1 + (bytes + kTextChunk - 1) / kTextChunk, wait, [&](Event& e, size_t i) {
    if (i == 0) return head(e);
    e.kind = EventKind::Text;
    size_t part = 0, at = (i - 1) * kTextChunk;  // the chunk's first byte: texts[part][at]
    while (at >= texts[part].size()) at -= texts[part++].size();
    for (size_t k = 0; k < kTextChunk && part < texts.size(); ++k) {
      e.text[k] = texts[part][at];
      if (++at == texts[part].size()) {
        at = 0;
        ++part;
        while (part < texts.size() && texts[part].empty()) ++part;
      }
    }
  });
}

// A fault's source and message follow it as text events, kTextChunk bytes each.
void Recorder::pushFault(const Trace& trace, uint32_t index, bool wait) {
  const FaultRecord& f = trace.faults[index];
  const std::string_view texts[] = {f.source, f.message};
  pushWithTexts(texts, wait, [&](Event& e) {
    e.kind = EventKind::Fault;
    e.index = index;
    e.timeNs = f.timeNs;
    e.fault = {static_cast<uint32_t>(f.source.size()), static_cast<uint32_t>(f.message.size())};
  });
}

void Recorder::externalWrite(const WriteRecord& r) {
  // Each text at most a u16's worth (a STRING variable holds at most 255 characters).
  auto cut = [](std::string_view t) { return t.substr(0, UINT16_MAX); };
  const std::string peer = writerAddress(r.writer), netId = r.writer.hasNetId ? formatNetId(r.writer.netId) : "";
  const std::string_view texts[kWriteTextCount] = {cut(peer),       cut(netId),      cut(r.variable),
                                                   cut(r.location), cut(r.oldValue), cut(r.newValue)};
  pushWithTexts(texts, false, [&](Event& e) {
    e.kind = EventKind::Write;
    e.index = writesSeen_;
    e.timeNs = r.virtualNs;
    e.write.wallNs = r.wallNs;
    for (size_t t = 0; t < kWriteTextCount; ++t) e.write.textBytes[t] = static_cast<uint16_t>(texts[t].size());
    e.write.protocol = static_cast<uint8_t>(r.writer.protocol);
    e.write.forced = r.writer.force;
  });
  ++writesSeen_;
}

void Recorder::follow(const Trace& trace, bool wait) {
  for (size_t k = 0; k < openActivities_.size();) {
    const uint32_t index = openActivities_[k];
    if (trace.activities[index].endNs < 0) {
      ++k;
      continue;
    }
    pushActivity(trace, index, wait);
    openActivities_[k] = openActivities_.back();
    openActivities_.pop_back();
  }
  for (; activitiesSeen_ < trace.activities.size(); ++activitiesSeen_) {
    const auto index = static_cast<uint32_t>(activitiesSeen_);
    pushActivity(trace, index, wait);
    if (trace.activities[index].endNs < 0) openActivities_.push_back(index);
  }
  for (; collisionsSeen_ < trace.collisions.size(); ++collisionsSeen_) {
    const CollisionRecord& c = trace.collisions[collisionsSeen_];
    push(1, wait, [&](Event& e, size_t) {
      e.kind = EventKind::Collision;
      e.index = static_cast<uint32_t>(collisionsSeen_);
      e.timeNs = c.timeNs;
      e.collision = {c.zone, c.deviceA, c.deviceB, c.activityA, c.activityB};
    });
  }
  for (; faultsSeen_ < trace.faults.size(); ++faultsSeen_) pushFault(trace, static_cast<uint32_t>(faultsSeen_), wait);
  if (trace.cyclesCompleted != cyclesSeen_) {
    cyclesSeen_ = trace.cyclesCompleted;
    push(1, wait, [&](Event& e, size_t) {
      e.kind = EventKind::Cycle;
      e.index = cyclesSeen_;
      e.timeNs = trace.cycleEndNs;
      e.cycle = {trace.cycleStartNs, trace.cycleEndNs};
    });
  }
}

void Recorder::tick(const Trace& trace, int64_t nowNs) {
  follow(trace, false);
  progressNs_.store(nowNs, std::memory_order_release);
}

void Recorder::end(const Trace& trace) {
  if (run_ < 0) return;
  follow(trace, true);
  progressNs_.store(trace.endNs, std::memory_order_release);
  stopWriter();
  if (!writer_.writeEnd(trace, drops(), error_) && error_.empty()) error_ = writer_.error();
}

void Recorder::production(uint32_t shift, const ProductionEvent& row) {
  if (run_ < 0 || !thread_.joinable()) return;  // not begun, or ended
  push(1, false, [&](Event& e, size_t) {
    e.kind = EventKind::Production;
    e.index = shift;
    e.timeNs = progressNs_.load(std::memory_order_relaxed);
    e.production = row;
  });
}

bool Recorder::recordProduction(const std::vector<ProductionRow>& rows) {
  if (run_ < 0 || thread_.joinable()) return false;  // not begun, or not ended yet
  if (writer_.writeProduction(rows)) return true;
  if (error_.empty()) error_ = writer_.error();
  return false;
}

void Recorder::stopWriter() {
  if (!thread_.joinable()) return;
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_one();
  thread_.join();
}

void Recorder::writerLoop() {
  int64_t lastCommitNs = monotonicNowNs();
  int64_t lastRetentionNs = lastCommitNs;
  int64_t committedProgressNs = -1;
  bool stopping = false;
  while (!stopping) {
    {
      std::unique_lock lock(mutex_);
      wake_.wait_for(lock, std::chrono::nanoseconds(kPollNs), [this] { return stopping_ || hurry_.load(std::memory_order_relaxed); });
      hurry_.store(false, std::memory_order_relaxed);
      stopping = stopping_;  // seen before draining: after it, nothing more is pushed
    }
    const int64_t nowNs = monotonicNowNs();
    const int64_t progressNs = progressNs_.load(std::memory_order_acquire);  // before the events it covers
    const size_t count = queue_.available();
    const bool due = nowNs - lastCommitNs >= options_.flushPeriodNs || count >= queue_.capacity() / 4 || stopping;
    if (!due || (count == 0 && progressNs == committedProgressNs)) continue;
    if (error_.empty() && !writer_.writeBatch(queue_, count, progressNs, drops())) error_ = writer_.error();
    if (!error_.empty()) drops_.fetch_add(count, std::memory_order_relaxed);  // lost with the database
    queue_.pop(count);
    lastCommitNs = nowNs;
    committedProgressNs = progressNs;
    if (options_.retention.any() && error_.empty() && nowNs - lastRetentionNs >= kRetentionPeriodNs) {
      lastRetentionNs = nowNs;
      int64_t pruned = pruneRuns(db_, options_.retention, run_, utcNowNs());
      if (pruned > 0) pruned_.fetch_add(pruned, std::memory_order_relaxed);
    }
  }
}

}  // namespace virtcom::history

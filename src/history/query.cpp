#include "history/query.hpp"

#include <algorithm>
#include <cstdlib>

#include "core/endpoint.hpp"
#include "core/signal_number.hpp"
#include "history/query_sql.hpp"
#include "history/schema.hpp"

namespace virtcom::history {

namespace {

constexpr const char* kRunColumns =
    "SELECT id, cell_name, cell_file, wall_start_ns, end_ns, end_reason, end_message, drops, writer_error, "
    "cycles_completed, cycle_start_ns, cycle_end_ns, timeline, "
    "(SELECT COUNT(*) FROM changes c WHERE c.run = runs.id), (SELECT COUNT(*) FROM activities a WHERE a.run = runs.id), "
    "(SELECT COUNT(*) FROM writes w WHERE w.run = runs.id) FROM runs";

RunSummary readRun(const Statement& s) {
  RunSummary r;
  r.id = s.columnInt(0);
  r.cellName = s.columnText(1);
  r.cellFile = s.columnText(2);
  r.wallStartNs = s.columnInt(3);
  r.endNs = s.columnInt(4);
  r.ended = !s.columnIsNull(5);
  r.endReason = s.columnText(5);
  r.endMessage = s.columnText(6);
  r.drops = s.columnInt(7);
  r.writerError = s.columnText(8);
  r.cyclesCompleted = s.columnInt(9);
  r.cycleStartNs = s.columnInt(10);
  r.cycleEndNs = s.columnInt(11);
  std::string timeline = s.columnText(12);
  for (size_t at = 0; at < timeline.size();) {
    size_t line = std::min(timeline.find('\n', at), timeline.size());
    r.timeline.push_back(timeline.substr(at, line - at));
    at = line + 1;
  }
  r.changes = s.columnInt(13);
  r.activities = s.columnInt(14);
  r.writes = s.columnInt(15);
  return r;
}

// The writer of a `writes` row back from its texts (Recorder::externalWrite wrote them).
ExternalWriter writerOf(const std::string& protocol, const std::string& peer, const std::string& netId, bool forced) {
  ExternalWriter w;
  for (size_t p = 0; p < kWriteProtocolCount; ++p)
    if (writeProtocolName(static_cast<WriteProtocol>(p)) == protocol) w.protocol = static_cast<WriteProtocol>(p);
  const size_t colon = peer.rfind(':');
  if (auto ip = parseIpv4(peer.substr(0, colon)); ip && colon != std::string::npos) {
    w.ipv4 = *ip;
    w.port = static_cast<uint16_t>(std::strtoul(peer.c_str() + colon + 1, nullptr, 10));
  }
  if (auto id = parseNetId(netId); id && !netId.empty()) {
    w.hasNetId = true;
    w.netId = *id;
  }
  w.force = forced;
  return w;
}

RunEnd runEndByName(const std::string& name) {
  for (RunEnd e : {RunEnd::Completed, RunEnd::TimeLimit, RunEnd::PlcFault, RunEnd::DeviceError, RunEnd::Collision, RunEnd::Interrupted})
    if (name == runEndName(e)) return e;
  return RunEnd::Interrupted;
}

constexpr const char* kDevices = "SELECT name, type, lane_group, busy_ns, energy_j FROM devices WHERE run = ?1 ORDER BY id";

// One signal's decimation while the changes of a range stream by: the first maxPoints changes
// as they are, and per time bucket the smallest, largest and last.
class Decimator {
 public:
  Decimator(ElemType type, int64_t fromNs, int64_t bucketNs, size_t buckets, size_t maxPoints)
      : type_(type), fromNs_(fromNs), bucketNs_(bucketNs), maxPoints_(maxPoints), buckets_(buckets) {}

  void add(const SignalChange& c) {
    if (series.changes++ < maxPoints_) series.points.push_back(c);
    const size_t index = std::min(static_cast<size_t>((c.timeNs - fromNs_) / bucketNs_), buckets_.size() - 1);
    Bucket& b = buckets_[index];
    const double v = signalNumber(type_, c.raw);
    if (!b.used || v < b.minValue) b.min = c, b.minValue = v;
    if (!b.used || v > b.maxValue) b.max = c, b.maxValue = v;
    b.last = c;
    b.used = true;
  }

  Series finish() {
    if (series.changes <= maxPoints_) return std::move(series);
    series.points.clear();
    for (const Bucket& b : buckets_) {
      if (!b.used) continue;
      SignalChange keep[] = {b.min, b.max, b.last};
      std::ranges::sort(keep, {}, &SignalChange::timeNs);
      for (size_t i = 0; i < 3; ++i)
        if (i == 0 || keep[i].timeNs != keep[i - 1].timeNs) series.points.push_back(keep[i]);
    }
    return std::move(series);
  }

  Series series;

 private:
  struct Bucket {
    SignalChange min, max, last;
    double minValue = 0, maxValue = 0;
    bool used = false;
  };
  ElemType type_;
  int64_t fromNs_, bucketNs_;
  size_t maxPoints_;
  std::vector<Bucket> buckets_;
};

// The parts of a trace that do not depend on the range: devices and labels.
void readDevicesAndLabels(HistoryReader& reader, Connection& db, int64_t run, Trace& trace) {
  Statement devices(db, kDevices);
  devices.bind(1, run);
  while (devices.step()) {
    trace.addDevice(devices.columnText(0), devices.columnText(1), devices.columnText(2));
    trace.totals.back() = {devices.columnInt(3), devices.columnDouble(4)};
  }
  trace.labels = reader.labels(run);
}

// A part of a run has no measured totals: each device's are its clipped activities'.
void totalsFromActivities(Trace& trace) {
  for (DeviceTotals& t : trace.totals) t = {};
  for (const ActivityRecord& a : trace.activities) {
    if (a.device >= trace.totals.size()) continue;
    const int64_t end = a.endNs < 0 ? trace.endNs : a.endNs;
    trace.totals[a.device].busyNs += std::max<int64_t>(0, end - a.startNs);
    trace.totals[a.device].energyJ += a.energyJ;
  }
  const auto& elided = trace.activities.elidedByDevice();  // a long range: its middle as sums
  for (size_t d = 0; d < elided.size() && d < trace.totals.size(); ++d) {
    trace.totals[d].busyNs += elided[d].busyNs;
    trace.totals[d].energyJ += elided[d].energyJ;
  }
}

// The cycles wholly inside [from, to], in order, into trace.cycles.
void readCycleList(Connection& db, int64_t run, int64_t from, int64_t to, Trace& trace) {
  Statement inside(db, "SELECT start_ns, end_ns FROM cycles WHERE run = ?1 AND start_ns >= ?2 AND end_ns <= ?3 ORDER BY number");
  inside.bind(1, run).bind(2, from).bind(3, to);
  while (inside.step()) trace.cycles.push_back({inside.columnInt(0) - from, inside.columnInt(1) - from});
}

// The cycles completed inside [from, to]; the last one wholly inside is the measured cycle.
void readCycles(Connection& db, int64_t run, int64_t from, int64_t to, Trace& trace) {
  Statement count(db, "SELECT COUNT(*) FROM cycles WHERE run = ?1 AND end_ns BETWEEN ?2 AND ?3");
  count.bind(1, run).bind(2, from).bind(3, to);
  if (count.step()) trace.cyclesCompleted = static_cast<uint32_t>(count.columnInt(0));
  readCycleList(db, run, from, to, trace);
  if (trace.cycles.empty()) return;
  trace.cycleStartNs = trace.cycles.back().startNs;
  trace.cycleEndNs = trace.cycles.back().endNs;
}

// Leaves out the rows that refer to a signal, device or label the trace does not have; their
// number. (Activities are checked as they are read: their log only appends.)
size_t dropDanglingRows(Trace& t) {
  const size_t before = t.changes.size() + t.activities.size() + t.collisions.size();
  const size_t signals = t.signals.size(), devices = t.devices.size(), labels = t.labels.size();
  std::erase_if(t.changes, [&](const SignalChange& c) { return c.tag >= signals; });
  std::erase_if(t.collisions, [&](const CollisionRecord& c) {
    return c.zone >= labels || c.deviceA >= devices || c.deviceB >= devices || c.activityA >= labels || c.activityB >= labels;
  });
  return before - (t.changes.size() + t.activities.size() + t.collisions.size());
}

}  // namespace

std::expected<HistoryReader, std::string> HistoryReader::open(const std::string& path) {
  auto db = openDatabase(path, OpenMode::Read);
  if (!db) return std::unexpected(db.error());
  return HistoryReader(std::move(*db));
}

std::vector<RunSummary> HistoryReader::runs() {
  std::vector<RunSummary> result;
  Statement s(db_, (std::string(kRunColumns) + " ORDER BY id").c_str());
  while (s.step()) result.push_back(readRun(s));
  return result;
}

std::optional<RunSummary> HistoryReader::run(int64_t id) {
  Statement s(db_, (std::string(kRunColumns) + " WHERE id = ?1").c_str());
  s.bind(1, id);
  if (!s.step()) return std::nullopt;
  return readRun(s);
}

int64_t HistoryReader::lastRunId() {
  int64_t id = 0;
  db_.queryInt("SELECT IFNULL(MAX(id), 0) FROM runs", id);
  return id;
}

std::vector<SignalInfo> HistoryReader::signals(int64_t run) {
  std::vector<SignalInfo> result;
  Statement s(db_, "SELECT name, type, initial FROM signals WHERE run = ?1 ORDER BY id");
  s.bind(1, run);
  while (s.step()) {
    SignalInfo info{s.columnText(0), ElemType::Bool, static_cast<uint64_t>(s.columnInt(2))};
    elemTypeByName(s.columnText(1), info.type);
    result.push_back(std::move(info));
  }
  return result;
}

std::vector<DeviceInfo> HistoryReader::devices(int64_t run) {
  std::vector<DeviceInfo> result;
  Statement s(db_, kDevices);
  s.bind(1, run);
  while (s.step()) result.push_back({s.columnText(0), s.columnText(1), s.columnText(2)});
  return result;
}

std::vector<std::string> HistoryReader::labels(int64_t run) {
  std::vector<std::string> result;
  Statement s(db_, "SELECT text FROM labels WHERE run = ?1 ORDER BY id");
  s.bind(1, run);
  while (s.step()) result.push_back(s.columnText(0));
  return result;
}

void HistoryReader::forEachChange(int64_t run, TimeRange range, const std::function<bool(const SignalChange&)>& fn) {
  Statement s(db_, sql::kChangesInRange);
  s.bind(1, run).bind(2, range.fromNs).bind(3, range.toNs);
  while (s.step())
    if (!fn({s.columnInt(0), static_cast<TagId>(s.columnInt(1)), static_cast<uint64_t>(s.columnInt(2))})) return;
}

std::vector<SignalChange> HistoryReader::changes(int64_t run, TimeRange range) {
  std::vector<SignalChange> result;
  forEachChange(run, range, [&result](const SignalChange& c) {
    result.push_back(c);
    return true;
  });
  return result;
}

std::vector<uint64_t> HistoryReader::valuesBefore(int64_t run, int64_t fromNs) {
  std::vector<uint64_t> values;
  for (const SignalInfo& s : signals(run)) values.push_back(s.initial);
  // The last change of each signal before fromNs (SQLite takes the bare column `raw` from the
  // row holding MAX(t_ns)).
  Statement s(db_, "SELECT signal, raw, MAX(t_ns) FROM changes WHERE run = ?1 AND t_ns < ?2 GROUP BY signal");
  s.bind(1, run).bind(2, fromNs);
  while (s.step()) {
    auto signal = static_cast<size_t>(s.columnInt(0));
    if (signal < values.size()) values[signal] = static_cast<uint64_t>(s.columnInt(1));
  }
  return values;
}

std::vector<Series> HistoryReader::series(int64_t run, const std::vector<TagId>& wanted, TimeRange range, size_t maxPoints) {
  const std::vector<SignalInfo> all = signals(run);
  auto summary = this->run(run);
  std::vector<Series> result;
  if (!summary) return result;
  const int64_t from = range.fromNs, to = std::max(from, std::min(range.toNs, summary->endNs));
  maxPoints = std::max<size_t>(maxPoints, 3);
  const size_t buckets = maxPoints / 3;
  const int64_t bucketNs = std::max<int64_t>(1, (to - from) / static_cast<int64_t>(buckets) + 1);
  std::vector<Decimator> plots;
  std::vector<int> plotOf(all.size(), -1);  // signal -> index into plots
  Statement before(db_, sql::kValueBefore);
  for (TagId signal : wanted) {
    if (signal >= all.size() || plotOf[signal] >= 0) continue;
    plotOf[signal] = static_cast<int>(plots.size());
    plots.emplace_back(all[signal].type, from, bucketNs, buckets, maxPoints);
    plots.back().series.signal = signal;
    plots.back().series.before = all[signal].initial;
    before.bind(1, run).bind(2, from).bind(3, static_cast<int64_t>(signal));
    if (before.step()) plots.back().series.before = static_cast<uint64_t>(before.columnInt(0));
    before.reset();
  }
  if (!plots.empty())
    forEachChange(run, {from, range.toNs}, [&](const SignalChange& c) {
      if (c.tag < plotOf.size() && plotOf[c.tag] >= 0) plots[static_cast<size_t>(plotOf[c.tag])].add(c);
      return true;
    });
  for (Decimator& d : plots) result.push_back(d.finish());
  return result;
}

std::vector<ProductionRow> HistoryReader::production(int64_t run) {
  std::vector<ProductionRow> result;
  Statement s(db_,
              "SELECT day, shift, start_wall_ns, end_wall_ns, watched_from_wall_ns, plan, plan_now, actual FROM production "
              "WHERE run = ?1 ORDER BY start_wall_ns");
  s.bind(1, run);
  while (s.step())
    result.push_back({s.columnText(0), s.columnText(1), s.columnInt(2), s.columnInt(3), s.columnInt(4), s.columnInt(5), s.columnDouble(6),
                      s.columnInt(7)});
  return result;
}

std::vector<WriteRecord> HistoryReader::writes(int64_t run, TimeRange range) {
  std::vector<WriteRecord> result;
  Statement s(db_,
              "SELECT t_ns, wall_ns, protocol, peer, netid, variable, location, old_value, new_value, forced FROM writes "
              "WHERE run = ?1 AND t_ns BETWEEN ?2 AND ?3 ORDER BY id");
  s.bind(1, run).bind(2, range.fromNs).bind(3, range.toNs);
  while (s.step())
    result.push_back({s.columnInt(0), s.columnInt(1), writerOf(s.columnText(2), s.columnText(3), s.columnText(4), s.columnInt(9) != 0),
                      s.columnText(5), s.columnText(6), s.columnText(7), s.columnText(8)});
  return result;
}

std::vector<ActivityRecord> HistoryReader::activities(int64_t run, TimeRange range) {
  std::vector<ActivityRecord> result;
  Statement s(db_, sql::kActivitiesInRange);
  s.bind(1, run).bind(2, range.fromNs).bind(3, range.toNs);
  while (s.step()) {
    ActivityRecord a;
    a.device = static_cast<uint32_t>(s.columnInt(0));
    a.label = static_cast<uint32_t>(s.columnInt(1));
    a.startNs = s.columnInt(2);
    a.endNs = s.columnInt(3);
    a.energyJ = s.columnDouble(4);
    a.errorCode = static_cast<int32_t>(s.columnInt(5));
    result.push_back(a);
  }
  return result;
}

Trace HistoryReader::trace(int64_t runId, TimeRange range, size_t* skipped) {
  Trace trace;
  auto summary = run(runId);
  if (!summary) return trace;
  const int64_t from = range.fromNs;
  const int64_t to = std::min(range.toNs, summary->endNs);
  trace.signals = signals(runId);
  if (!range.whole()) {
    std::vector<uint64_t> before = valuesBefore(runId, from);
    for (size_t i = 0; i < trace.signals.size(); ++i) trace.signals[i].initial = before[i];
  }
  forEachChange(runId, {from, to}, [&](const SignalChange& c) {
    trace.changes.push_back({c.timeNs - from, c.tag, c.raw});
    return true;
  });
  readDevicesAndLabels(*this, db_, runId, trace);
  size_t danglingActivities = 0;
  for (ActivityRecord a : activities(runId, {from, to})) {
    if (a.device >= trace.devices.size() || a.label >= trace.labels.size()) {
      ++danglingActivities;
      continue;
    }
    a.startNs = std::max(a.startNs, from) - from;
    if (a.endNs >= 0) a.endNs = std::min(a.endNs, to) - from;
    trace.activities.push_back(a);
  }
  Statement collisions(db_,
                       "SELECT t_ns, zone, device_a, device_b, activity_a, activity_b FROM collisions "
                       "WHERE run = ?1 AND t_ns BETWEEN ?2 AND ?3 ORDER BY id");
  collisions.bind(1, runId).bind(2, from).bind(3, to);
  while (collisions.step()) {
    auto u32 = [&](int column) { return static_cast<uint32_t>(collisions.columnInt(column)); };
    trace.collisions.push_back({collisions.columnInt(0) - from, u32(1), u32(2), u32(3), u32(4), u32(5)});
  }
  Statement faults(db_, "SELECT t_ns, source, message FROM faults WHERE run = ?1 AND t_ns BETWEEN ?2 AND ?3 ORDER BY id");
  faults.bind(1, runId).bind(2, from).bind(3, to);
  while (faults.step()) trace.faults.push_back({faults.columnInt(0) - from, faults.columnText(1), faults.columnText(2)});
  // The audited writes of the range for the reports (counted, and the first listed), at times
  // from the range's start as everything else; a run that recorded none (no client wrote, or the
  // audit was off) says nothing about them.
  for (WriteRecord& w : writes(runId, {from, to})) {
    w.virtualNs -= from;
    trace.keepExternalWrite(w);
  }
  trace.writesAudited = summary->writes > 0;
  trace.endNs = to - from;
  trace.end = summary->ended ? runEndByName(summary->endReason) : RunEnd::Interrupted;
  trace.endMessage = summary->ended ? summary->endMessage : "the recording stopped before the run ended (the process was killed)";
  if (range.whole()) {
    trace.cyclesCompleted = static_cast<uint32_t>(summary->cyclesCompleted);
    trace.cycleStartNs = summary->cycleStartNs;
    trace.cycleEndNs = summary->cycleEndNs;
    readCycleList(db_, runId, from, to, trace);
  } else {
    readCycles(db_, runId, from, to, trace);
  }
  if (!range.whole()) totalsFromActivities(trace);
  const size_t dangling = dropDanglingRows(trace) + danglingActivities;
  if (skipped) *skipped = dangling;
  return trace;
}

}  // namespace virtcom::history

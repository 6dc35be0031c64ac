#include "history/run_writer.hpp"

#include <algorithm>

#include "core/external_write.hpp"
#include "core/iec_value.hpp"

namespace virtcom::history {

namespace {

// The scope of a transaction: rolled back unless committed.
class Transaction {
 public:
  explicit Transaction(Connection& db) : db_(db), open_(db.exec("BEGIN")) {}
  ~Transaction() {
    if (open_) db_.exec("ROLLBACK");
  }
  bool began() const { return open_; }
  bool commit() {
    open_ = !db_.exec("COMMIT");
    return !open_;
  }

 private:
  Connection& db_;
  bool open_;
};

}  // namespace

RunWriter::RunWriter(Connection& db)
    : db_(db),
      change_(db, "INSERT OR REPLACE INTO changes (run, t_ns, signal, raw) VALUES (?1, ?2, ?3, ?4)"),
      activity_(db, "INSERT OR REPLACE INTO activities (run, id, device, label, start_ns, end_ns, energy_j, error_code) "
                    "VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8)"),
      collision_(db, "INSERT OR REPLACE INTO collisions (run, id, t_ns, zone, device_a, device_b, activity_a, activity_b) "
                     "VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8)"),
      fault_(db, "INSERT OR REPLACE INTO faults (run, id, t_ns, source, message) VALUES (?1, ?2, ?3, ?4, ?5)"),
      cycle_(db, "INSERT OR REPLACE INTO cycles (run, number, start_ns, end_ns) VALUES (?1, ?2, ?3, ?4)"),
      progress_(db, "UPDATE runs SET end_ns = ?2, drops = ?3 WHERE id = ?1"),
      label_(db, "INSERT OR IGNORE INTO labels (run, id, text) VALUES (?1, ?2, ?3)"),
      // The day is the local date the shift started on: local wall ns read as if they were UTC.
      production_(db, "INSERT OR REPLACE INTO production (run, start_wall_ns, end_wall_ns, watched_from_wall_ns, day, shift, plan, "
                      "plan_now, actual) VALUES (?1, ?2, ?3, ?4, strftime('%Y-%m-%d', ?2 / 1000000000, 'unixepoch'), ?5, ?6, ?7, ?8)"),
      write_(db, "INSERT OR REPLACE INTO writes (run, id, t_ns, wall_ns, protocol, peer, netid, variable, location, old_value, "
                 "new_value, forced) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12)") {}

bool RunWriter::fail() {
  if (error_.empty()) error_ = db_.errorText();
  return false;
}

bool RunWriter::writeLabels(const Trace& trace) {
  for (size_t i = 0; i < trace.labels.size(); ++i)
    if (!label_.bind(1, run_).bind(2, static_cast<int64_t>(i)).bind(3, trace.labels[i]).run()) return fail();
  return true;
}

int64_t RunWriter::writeStart(const Trace& trace, const RunIdentity& identity) {
  Transaction tx(db_);
  std::string timeline;
  for (const std::string& name : identity.timeline) timeline += (timeline.empty() ? "" : "\n") + name;
  Statement run(db_, "INSERT INTO runs (cell_name, cell_file, wall_start_ns, timeline) VALUES (?1, ?2, ?3, ?4)");
  if (!tx.began() || !run.bind(1, identity.cellName).bind(2, identity.cellFile).bind(3, identity.wallStartNs).bind(4, timeline).run())
    return fail(), -1;
  run_ = db_.lastInsertRowid();
  shiftNames_ = identity.shiftNames;
  Statement signal(db_, "INSERT INTO signals (run, id, name, type, initial) VALUES (?1, ?2, ?3, ?4, ?5)");
  for (size_t i = 0; i < trace.signals.size(); ++i) {
    const SignalInfo& s = trace.signals[i];
    if (!signal.bind(1, run_).bind(2, static_cast<int64_t>(i)).bind(3, s.name).bind(4, elemTypeInfo(s.type).name)
             .bind(5, static_cast<int64_t>(s.initial)).run())
      return fail(), -1;
  }
  Statement device(db_, "INSERT INTO devices (run, id, name, type, lane_group) VALUES (?1, ?2, ?3, ?4, ?5)");
  for (size_t i = 0; i < trace.devices.size(); ++i) {
    const DeviceInfo& d = trace.devices[i];
    if (!device.bind(1, run_).bind(2, static_cast<int64_t>(i)).bind(3, d.name).bind(4, d.type).bind(5, d.group).run()) return fail(), -1;
  }
  if (!writeLabels(trace) || !tx.commit()) return fail(), -1;
  return run_;
}

std::string_view RunWriter::readTexts(const EventQueue& queue, size_t& i, size_t bytes) {
  text_.clear();
  for (size_t k = 0; k < bytes; k += kTextChunk) text_.append(queue.at(++i).text, std::min(kTextChunk, bytes - k));
  return text_;
}

void RunWriter::writeFault(const EventQueue& queue, size_t& i) {
  const Event& header = queue.at(i);
  std::string_view text = readTexts(queue, i, header.fault.sourceBytes + header.fault.messageBytes);
  fault_.bind(1, run_).bind(2, static_cast<int64_t>(header.index)).bind(3, header.timeNs)
      .bind(4, text.substr(0, header.fault.sourceBytes)).bind(5, text.substr(header.fault.sourceBytes));
}

void RunWriter::writeExternalWrite(const EventQueue& queue, size_t& i) {
  const Event& header = queue.at(i);
  const WriteEvent w = header.write;
  size_t bytes = 0;
  for (uint16_t n : w.textBytes) bytes += n;
  write_.bind(1, run_).bind(2, static_cast<int64_t>(header.index)).bind(3, header.timeNs).bind(4, w.wallNs)
      .bind(5, writeProtocolName(static_cast<WriteProtocol>(w.protocol))).bind(12, int64_t{w.forced});
  std::string_view text = readTexts(queue, i, bytes);
  for (size_t t = 0; t < kWriteTextCount; ++t) {
    write_.bind(static_cast<int>(6 + t), text.substr(0, w.textBytes[t]));
    text.remove_prefix(w.textBytes[t]);
  }
}

// Binds event i (and, for a fault or write, its text events, advancing i past them) and runs it.
bool RunWriter::writeEvent(const EventQueue& queue, size_t& i) {
  const Event& e = queue.at(i);
  const int64_t index = e.index;
  switch (e.kind) {
    case EventKind::Change:
      return change_.bind(1, run_).bind(2, e.timeNs).bind(3, index).bind(4, static_cast<int64_t>(e.raw)).run();
    case EventKind::Activity: {
      const ActivityEvent& a = e.activity;
      activity_.bind(1, run_).bind(2, index).bind(3, int64_t{a.device}).bind(4, int64_t{a.label}).bind(5, a.startNs);
      if (a.endNs >= 0) activity_.bind(6, a.endNs);
      return activity_.bind(7, a.energyJ).bind(8, int64_t{a.errorCode}).run();
    }
    case EventKind::Collision: {
      const CollisionEvent& c = e.collision;
      return collision_.bind(1, run_).bind(2, index).bind(3, e.timeNs).bind(4, int64_t{c.zone}).bind(5, int64_t{c.deviceA})
          .bind(6, int64_t{c.deviceB}).bind(7, int64_t{c.activityA}).bind(8, int64_t{c.activityB}).run();
    }
    case EventKind::Fault:
      writeFault(queue, i);
      return fault_.run();
    case EventKind::Cycle:
      return cycle_.bind(1, run_).bind(2, index).bind(3, e.cycle.startNs).bind(4, e.cycle.endNs).run();
    case EventKind::Production: {
      const ProductionEvent& p = e.production;
      if (e.index >= shiftNames_.size()) return true;  // not a shift of the plan the run was begun with
      return production_.bind(1, run_).bind(2, p.startWallNs).bind(3, p.endWallNs).bind(4, p.watchedFromWallNs)
          .bind(5, shiftNames_[e.index]).bind(6, int64_t{p.plan}).bind(7, p.planNow).bind(8, int64_t{p.actual}).run();
    }
    case EventKind::Write:
      writeExternalWrite(queue, i);
      return write_.run();
    case EventKind::Text:
      return true;  // only after a fault or write, which consumed it
  }
  return true;
}

bool RunWriter::writeBatch(const EventQueue& queue, size_t count, int64_t progressNs, uint64_t drops) {
  Transaction tx(db_);
  if (!tx.began()) return fail();
  for (size_t i = 0; i < count; ++i)
    if (!writeEvent(queue, i)) return fail();
  if (!progress_.bind(1, run_).bind(2, progressNs).bind(3, static_cast<int64_t>(drops)).run()) return fail();
  return tx.commit() || fail();
}

bool RunWriter::writeEnd(const Trace& trace, uint64_t drops, const std::string& writerError) {
  Transaction tx(db_);
  if (!tx.began()) return fail();
  Statement run(db_,
                "UPDATE runs SET end_ns = ?2, end_reason = ?3, end_message = ?4, cycles_completed = ?5, cycle_start_ns = ?6, "
                "cycle_end_ns = ?7, drops = ?8, writer_error = ?9 WHERE id = ?1");
  if (!run.bind(1, run_).bind(2, trace.endNs).bind(3, std::string_view(runEndName(trace.end))).bind(4, trace.endMessage)
           .bind(5, int64_t{trace.cyclesCompleted}).bind(6, trace.cycleStartNs).bind(7, trace.cycleEndNs)
           .bind(8, static_cast<int64_t>(drops)).bind(9, writerError).run())
    return fail();
  Statement totals(db_, "UPDATE devices SET busy_ns = ?3, energy_j = ?4 WHERE run = ?1 AND id = ?2");
  for (size_t i = 0; i < trace.totals.size(); ++i)
    if (!totals.bind(1, run_).bind(2, static_cast<int64_t>(i)).bind(3, trace.totals[i].busyNs).bind(4, trace.totals[i].energyJ).run())
      return fail();
  return (writeLabels(trace) && tx.commit()) || fail();
}

bool RunWriter::writeProduction(const std::vector<ProductionRow>& rows) {
  Transaction tx(db_);
  if (!tx.began()) return fail();
  Statement row(db_,
                "INSERT OR REPLACE INTO production (run, start_wall_ns, end_wall_ns, watched_from_wall_ns, day, shift, plan, plan_now, "
                "actual) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9)");
  for (const ProductionRow& r : rows)
    if (!row.bind(1, run_).bind(2, r.startWallNs).bind(3, r.endWallNs).bind(4, r.watchedFromWallNs).bind(5, r.day).bind(6, r.shift)
             .bind(7, r.plan).bind(8, r.planNow).bind(9, r.actual).run())
      return fail();
  return tx.commit() || fail();
}

}  // namespace virtcom::history

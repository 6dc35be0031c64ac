#include "cli/history_options.hpp"

#include <filesystem>
#include <iostream>

namespace virtcom::cli {

void addHistoryOptions(CLI::App* cmd, HistoryRecordOptions& o) {
  cmd->add_option("--history", o.path,
                  "record every signal change, activity, fault, collision and cycle into this SQLite file (created if missing; "
                  "see virtcom history and docs/history.md)");
  cmd->add_option("--history-keep-days", o.keepDays, "with --history: delete runs older than this many days (default: keep all)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--history-max-mb", o.maxMb, "with --history: delete the oldest runs while the file is larger than this (MiB)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--history-queue", o.queueEvents,
                  "with --history: events buffered between the simulation and the database writer (default 65536); "
                  "when full, a run paced to the wall clock (serve, --speed) drops events and counts them, a run in virtual time waits")
      ->check(CLI::PositiveNumber);
}

std::expected<std::unique_ptr<history::Recorder>, std::string> openRecorder(const HistoryRecordOptions& o, const cell::Cell& cell,
                                                                           const std::string& cellFile,
                                                                           std::vector<std::string> timeline, bool paced) {
  if (o.path.empty()) return nullptr;
  history::RecorderOptions options;
  options.cellName = cell.name;
  std::error_code ec;
  auto absolute = std::filesystem::absolute(cellFile, ec);
  options.cellFile = ec ? cellFile : absolute.lexically_normal().string();
  options.timeline = std::move(timeline);
  for (const PlannedShift& s : cell.plan.shifts) options.shiftNames.push_back(s.name);
  options.queueEvents = o.queueEvents;
  options.waitWhenFull = !paced;
  options.retention = {o.keepDays, o.maxMb * 1024 * 1024};
  auto recorder = history::Recorder::open(o.path, std::move(options));
  if (!recorder) return std::unexpected("--history: " + recorder.error());
  if ((*recorder)->pruned() > 0) std::cerr << "history: deleted " << (*recorder)->pruned() << " old run(s) from " << o.path << "\n";
  return std::move(*recorder);
}

bool reportRecording(const HistoryRecordOptions& o, const history::Recorder& recorder) {
  if (!recorder.error().empty()) {
    std::cerr << "error: --history: recording into " << o.path << " failed: " << recorder.error() << "\n";
    return false;
  }
  std::cerr << "history: run " << recorder.runId() << " recorded in " << o.path << "\n";
  if (recorder.drops() > 0)
    std::cerr << "warning: history: " << recorder.drops() << " event(s) dropped: the database writer fell behind (queue of "
              << o.queueEvents << " events full); the run's row records the count\n";
  return true;
}

bool recordNextRun(const HistoryRecordOptions& o, std::unique_ptr<history::Recorder>& recorder, const cell::Cell& cell,
                   const std::string& cellFile, std::vector<std::string> timeline, bool paced, std::vector<TraceSink*>& sinks) {
  if (!recorder) return true;
  std::erase(sinks, recorder.get());
  bool ok = reportRecording(o, *recorder);
  recorder.reset();
  auto next = openRecorder(o, cell, cellFile, std::move(timeline), paced);
  if (!next) {
    std::cerr << "error: " << next.error() << "\n";
    return false;
  }
  recorder = std::move(*next);
  sinks.push_back(recorder.get());
  return ok;
}

WriteAudit::Sink intoRecorder(std::unique_ptr<history::Recorder>& recorder) {
  return [&recorder](const WriteRecord& r) {
    if (recorder) recorder->externalWrite(r);
  };
}

}  // namespace virtcom::cli

#pragma once
// The historian options that `run` and `serve` share (docs/history.md): --history FILE and its
// retention limits, one definition so both commands record alike.
#include <cstdint>
#include <expected>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cell/cell.hpp"
#include "history/recorder.hpp"
#include "core/write_audit.hpp"

namespace virtcom::cli {

struct HistoryRecordOptions {
  std::string path;         // --history; empty: not recorded
  int64_t keepDays = 0;     // --history-keep-days
  int64_t maxMb = 0;        // --history-max-mb
  size_t queueEvents = history::RecorderOptions{}.queueEvents;  // --history-queue
};

// Adds --history, --history-keep-days, --history-max-mb and --history-queue to `cmd`.
void addHistoryOptions(CLI::App* cmd, HistoryRecordOptions& o);

// The recorder for `cell` (null without --history), or the error naming the file.
// `timeline`: the signals the run's report shows, kept with the run for `virtcom history --report`.
// `paced`: the run follows the wall clock (serve, --speed, an external PLC), so a full queue
// drops events; otherwise the simulation waits for the writer and every event is recorded.
std::expected<std::unique_ptr<history::Recorder>, std::string> openRecorder(const HistoryRecordOptions& o, const cell::Cell& cell,
                                                                           const std::string& cellFile,
                                                                           std::vector<std::string> timeline, bool paced);

// After the run: one line on stderr naming the run recorded, and a warning for dropped events
// or a database failure. False if the recording failed.
bool reportRecording(const HistoryRecordOptions& o, const history::Recorder& recorder);

// A reset from the HMI starts a new run: the one that ended is reported (reportRecording) and
// a new recorder over the fresh `cell` takes `recorder`'s place among `sinks` (nothing without
// --history). False (after a message) if the run's recording failed or the file cannot be
// opened again; the runs then go on unrecorded.
bool recordNextRun(const HistoryRecordOptions& o, std::unique_ptr<history::Recorder>& recorder, const cell::Cell& cell,
                   const std::string& cellFile, std::vector<std::string> timeline, bool paced, std::vector<TraceSink*>& sinks);

// Where the write audit puts each record besides the log: into the recorder in use (a reset
// replaces it), or nowhere while none records.
WriteAudit::Sink intoRecorder(std::unique_ptr<history::Recorder>& recorder);

}  // namespace virtcom::cli

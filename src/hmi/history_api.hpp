#pragma once
// The HMI's history answers (docs/hmi.md, "History"): the runs a history database holds and,
// for a run and a virtual-time range, the activities overlapping it (the Gantt chart's rows),
// chosen signals decimated for the trend (history::HistoryReader::series) and the state at one
// time (the layout's device states). Over its own read connection, which WAL lets read while a
// recorder of the same process writes; one request at a time (a SQLite connection is not shared
// between threads here). Never on the simulation's thread: the HTTP pool's.
#include <expected>
#include <memory>
#include <mutex>
#include <string>

#include "history/query.hpp"
#include "hmi/request.hpp"

namespace virtcom::hmi {

class HistoryApi {
 public:
  // Opens `path` for reading; error text naming the file if it is no history.
  static std::expected<std::unique_ptr<HistoryApi>, std::string> open(const std::string& path);
  explicit HistoryApi(history::HistoryReader reader) : reader_(std::move(reader)) {}

  // Route::HistoryRuns, HistoryRange, HistoryState; 404 for a run the file does not have, 400
  // for a signal the run did not record. JSON schemas in docs/hmi.md.
  Response handle(const ParsedRequest& request);

 private:
  Response runs();
  Response range(const ParsedRequest& r);
  Response state(const ParsedRequest& r);

  std::mutex mutex_;
  history::HistoryReader reader_;
};

}  // namespace virtcom::hmi

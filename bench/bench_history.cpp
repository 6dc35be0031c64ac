// The historian (src/history, docs/history.md): what recording costs the simulation thread per
// signal change, and how many changes per second the writer thread commits to SQLite
// (docs/performance.md, "History").
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>

#include "history/recorder.hpp"
#include "history/run_writer.hpp"
#include "history/schema.hpp"

namespace virtcom::bench {
namespace {

namespace fs = std::filesystem;

// A fresh database file in the temporary directory, removed with its WAL files when done.
struct ScratchDb {
  explicit ScratchDb(const std::string& name) : path((fs::temp_directory_path() / name).string()) { remove(); }
  ~ScratchDb() { remove(); }
  void remove() const {
    for (const char* suffix : {"", "-wal", "-shm"}) fs::remove(path + suffix);
  }
  std::string path;
};

// 64 signals, like a small cell's bus.
Trace benchTrace() {
  Trace t;
  for (int i = 0; i < 64; ++i) t.signals.push_back({"Dev" + std::to_string(i) + ".sig", ElemType::Dint, 0});
  return t;
}

// The simulation thread's side: Recorder::change(), one tick() per 16 changes, with the writer
// thread committing concurrently. A fixed 60000 changes (+ 3750 ticks' nothing) fit the default
// queue of 65536 events, so every push is the normal path, never the drop path; `drops` checks it.
void BM_HistoryChangeOnScanThread(benchmark::State& state) {
  ScratchDb db("virtcom_bench_history_scan.sqlite");
  auto recorder = history::Recorder::open(db.path, {});
  if (!recorder) {
    state.SkipWithError(recorder.error().c_str());
    return;
  }
  Trace t = benchTrace();
  (*recorder)->begin(t);
  int64_t now = 0;
  uint64_t n = 0;
  for (auto _ : state) {
    (*recorder)->change({now, static_cast<TagId>(n & 63), n});
    if ((++n & 15) == 0) (*recorder)->tick(t, now += 1'000'000);
  }
  t.endNs = now;
  (*recorder)->end(t);
  state.counters["drops"] = static_cast<double>((*recorder)->drops());
  state.SetItemsProcessed(state.iterations());
}

// The writer thread's side: one transaction of `range(0)` changes from the queue, as
// RunWriter::writeBatch commits them. items_per_second = changes committed per second.
void BM_HistoryWriterCommit(benchmark::State& state) {
  ScratchDb scratch("virtcom_bench_history_writer.sqlite");
  auto db = history::openDatabase(scratch.path, history::OpenMode::Record);
  if (!db) {
    state.SkipWithError(db.error().c_str());
    return;
  }
  history::RunWriter writer(*db);
  writer.writeStart(benchTrace(), {"bench", "bench.yaml", 0, {}, {}});
  const auto batch = static_cast<size_t>(state.range(0));
  history::EventQueue queue(batch);
  int64_t now = 0;
  for (auto _ : state) {
    state.PauseTiming();
    for (size_t i = 0; i < batch; ++i)
      queue.tryPush(1, [&](history::Event& e, size_t) {
        e.kind = history::EventKind::Change;
        e.index = static_cast<uint32_t>(i & 63);
        e.timeNs = now + static_cast<int64_t>(i / 16) * 1'000'000;
        e.raw = i;
      });
    now += static_cast<int64_t>(batch / 16 + 1) * 1'000'000;
    state.ResumeTiming();
    if (!writer.writeBatch(queue, batch, now, 0)) state.SkipWithError(writer.error().c_str());
    queue.pop(batch);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(batch));
}

BENCHMARK(BM_HistoryChangeOnScanThread)->Name("history/change_on_scan_thread")->Iterations(60000)->Repetitions(5)->ReportAggregatesOnly();
BENCHMARK(BM_HistoryWriterCommit)->Name("history/writer_commit")->Arg(1024)->Arg(16384)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace virtcom::bench

#pragma once
// Signal histories for waveform viewers and spreadsheets: written as the run goes (VcdWriter,
// CsvWriter are TraceSinks on an output stream, so a run of any length needs no memory for
// them), or from a finished trace's Trace::signals and Trace::changes (vcdReport, csvChanges:
// the same writers fed from memory, so both give the same bytes).
#include <ostream>
#include <string>
#include <vector>

#include "core/trace.hpp"

namespace virtcom::report {

// IEEE 1364-2005 §18 four-state VCD, timescale 1 ns, loadable by GTKWave. All signals sit in
// `$scope module virtcom`; a name with a '.' goes into a nested `$scope module <prefix>` (the
// part before the first '.', usually the device) as the rest of the name. BOOL -> `wire 1`,
// REAL/LREAL -> `real 64`, signed integers/TIME/dates -> `integer <bits>`, unsigned and bit
// strings -> `wire <bits>` (binary vectors). STRING/WSTRING signals are listed in a $comment
// and not dumped. Initial values go in `#0 $dumpvars`, then every change in order; a final
// `#<endNs>` timestamp marks the end of the run. Changes naming an unknown tag or a negative
// time are skipped. No $date (the output is deterministic).
std::string vcdReport(const Trace& trace);

class VcdWriter final : public TraceSink {
 public:
  explicit VcdWriter(std::ostream& out) : out_(out) {}
  void begin(const Trace& trace) override;
  void change(const SignalChange& c) override;
  void end(const Trace& trace) override;

 private:
  std::ostream& out_;
  const Trace* trace_ = nullptr;
  std::vector<std::string> ids_;  // per tag; empty: not dumped
  int64_t now_ = 0;
};

// RFC 4180 CSV with header `time_s,signal,value`: one row per signal for its initial value at
// time 0, then one row per change in trace order. time_s has 9 decimals (exact ns); BOOL is
// 0/1, integers decimal, reals the shortest round-trip text. Signal names are quoted when needed.
std::string csvChanges(const Trace& trace);

class CsvWriter final : public TraceSink {
 public:
  explicit CsvWriter(std::ostream& out) : out_(out) {}
  void begin(const Trace& trace) override;
  void change(const SignalChange& c) override;
  void end(const Trace&) override {}

 private:
  std::ostream& out_;
  const Trace* trace_ = nullptr;
  std::vector<std::string> names_;  // per tag, CSV-quoted
};

// Feeds a finished trace's initial values and kept changes to a sink, as a run would have.
void replay(const Trace& trace, TraceSink& sink);

}  // namespace virtcom::report

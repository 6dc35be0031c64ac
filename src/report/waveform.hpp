#pragma once
// Signal histories for waveform viewers and spreadsheets, from Trace::signals and Trace::changes.
#include <string>

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

// RFC 4180 CSV with header `time_s,signal,value`: one row per signal for its initial value at
// time 0, then one row per change in trace order. time_s has 9 decimals (exact ns); BOOL is
// 0/1, integers decimal, reals the shortest round-trip text. Signal names are quoted when needed.
std::string csvChanges(const Trace& trace);

}  // namespace virtcom::report

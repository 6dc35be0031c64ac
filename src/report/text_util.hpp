#pragma once
// Text helpers shared by the report writers: locale-independent number formatting, UTF-8
// sanitising and escaping, safe name lookups into a Trace and signal value decoding. Internal to
// src/report (not part of its public API).
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/signal_number.hpp"
#include "core/trace.hpp"

namespace virtcom::report {

// `v` with exactly `decimals` digits after the point ("12.500"); "nan"/"inf" pass through. Never
// depends on the C locale.
std::string formatFixed(double v, int decimals);
// Nanoseconds as seconds with `decimals` digits ("1.500" for 1'500'000'000 ns, 3 decimals).
std::string formatSeconds(int64_t ns, int decimals);
// Shortest text that reads back as the same double ("0.1", "4871.2", "1e+20").
std::string formatShortest(double v);
inline double nsToSeconds(int64_t ns) { return static_cast<double>(ns) / 1e9; }

// Replaces invalid UTF-8 sequences and C0/DEL control characters (except tab) with U+FFFD, so
// names from user files can go into any output format.
std::string sanitizeUtf8(std::string_view s);
// Escapes & < > " ' for HTML/XML text and attribute values; sanitises UTF-8 first.
std::string escapeHtml(std::string_view s);
// Number of code points (a terminal column each, good enough for names in a table).
size_t displayWidth(std::string_view s);
// At most `width` code points; a cut name ends in `cutMark` (one column wide). Sanitised.
std::string fitWidth(std::string_view s, size_t width, std::string_view cutMark = "~");
// `s` padded with spaces to `width` code points, on the right (left aligned) or on the left.
std::string padRight(std::string_view s, size_t width);
std::string padLeft(std::string_view s, size_t width);

// Stable machine name of how a run ended ("time_limit"), for JSON.
const char* runEndKey(RunEnd e);

// Lookups that never index out of range: a bad index reads as "?" (reports must render any trace).
const std::string& deviceName(const Trace& t, uint32_t device);
const std::string& labelName(const Trace& t, uint32_t label);
// End of an activity for reporting: still running at the end of the run (endNs == -1) -> the run's
// end, never before its start.
int64_t activityEndNs(const Trace& t, const ActivityRecord& a);
// The indices of the activities a report shows, in start order: all of a short run; of a long one
// the first and last it kept and those still running in between (docs/report.md "Long runs").
std::vector<uint32_t> heldActivities(const Trace& t);

// A signal's raw TagBus value as text for tables and CSV (as a number: core/signal_number.hpp).
std::string signalText(ElemType type, uint64_t raw);
// STRING/WSTRING values do not fit a raw slot: such signals are not plotted or dumped.
bool isPlottable(ElemType type);
// A value of a signal of `type` (from signalNumber) as a chart label, written as an engineer
// reads that type: bit strings in hex with the type's width (WORD 16#00FF), TIME as IEC text
// (T#1s500ms; LTIME from ns), REAL/LREAL rounded to at most 3 decimals (1125, not
// 1124.9999999999977; very small or large values in 4 significant digits), others in decimal.
std::string chartValueText(ElemType type, double value);

}  // namespace virtcom::report

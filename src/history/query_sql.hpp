#pragma once
// The SQL of the range queries the HMI sends at every scroll and zoom (HistoryReader::series and
// activities), in one place so that tests/unit/history/query_plan_test.cpp can check with
// EXPLAIN QUERY PLAN that each searches an index instead of scanning a table.
namespace virtcom::history::sql {

// ?1 run, ?2 from, ?3 to: one range search of the (run, t_ns, signal) key.
inline constexpr const char* kChangesInRange =
    "SELECT t_ns, signal, raw FROM changes WHERE run = ?1 AND t_ns BETWEEN ?2 AND ?3 ORDER BY t_ns, signal";
// ?1 run, ?2 time, ?3 signal: the key searched backwards from the time; the cost is the changes
// (of every signal) between the signal's last change and the time (no index by signal: it would
// cost every recorded change a second B-tree insert).
inline constexpr const char* kValueBefore =
    "SELECT raw FROM changes WHERE run = ?1 AND t_ns < ?2 AND signal = ?3 ORDER BY t_ns DESC LIMIT 1";
// ?1 run, ?2 from, ?3 to: the (run, start_ns) index up to the range's end.
inline constexpr const char* kActivitiesInRange =
    "SELECT device, label, start_ns, IFNULL(end_ns, -1), energy_j, error_code FROM activities "
    "WHERE run = ?1 AND start_ns <= ?3 AND (end_ns IS NULL OR end_ns >= ?2) ORDER BY start_ns, id";

}  // namespace virtcom::history::sql

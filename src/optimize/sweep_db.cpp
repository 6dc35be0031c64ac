// Sweep databases: the schema, writing a slice's rows, reading them back, merging slices.
#include "optimize/sweep_db.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "history/sqlite.hpp"

namespace virtcom::optimize {

namespace {

// Everything a database holds, read or about to be written.
struct Contents {
  std::vector<std::pair<std::string, std::string>> sweep;  // key, value: what was swept
  std::vector<SweepSlice> slices;
  report::SweepTable table;
};

std::string quoted(const std::string& name) {
  std::string s = "\"";
  for (char c : name) s += c == '"' ? std::string("\"\"") : std::string(1, c);
  return s + "\"";
}

std::string joinLines(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : "\n") + n;
  return s;
}

std::string write(const std::string& path, const Contents& c) {
  std::error_code ec;
  std::filesystem::remove(path, ec);
  history::Connection db;
  if (!db.open(path, true)) return "cannot create '" + path + "': " + db.errorText();
  std::string ddl =
      "BEGIN;"
      "CREATE TABLE sweep(key TEXT PRIMARY KEY, value TEXT NOT NULL);"
      "CREATE TABLE slices(slice INTEGER NOT NULL, slices INTEGER NOT NULL, points INTEGER NOT NULL);"
      "CREATE TABLE points(point INTEGER PRIMARY KEY";
  std::string insert = "INSERT INTO points VALUES(?";
  for (const std::string& p : c.table.parameters) {
    ddl += ", " + quoted(p) + " TEXT NOT NULL";
    insert += ",?";
  }
  ddl += ", cycle_s REAL, energy_J REAL, result TEXT NOT NULL);";
  insert += ",?,?,?)";
  if (!db.exec(ddl.c_str())) return "'" + path + "': " + db.errorText();
  history::Statement meta(db, "INSERT INTO sweep VALUES(?, ?)");
  for (const auto& [key, value] : c.sweep)
    if (!meta.bind(1, key).bind(2, value).run()) return "'" + path + "': " + db.errorText();
  history::Statement slice(db, "INSERT INTO slices VALUES(?, ?, ?)");
  for (const SweepSlice& s : c.slices)
    if (!slice.bind(1, static_cast<int64_t>(s.index)).bind(2, static_cast<int64_t>(s.count)).bind(3, static_cast<int64_t>(s.points)).run())
      return "'" + path + "': " + db.errorText();
  history::Statement row(db, insert.c_str());
  const int kpis = 2 + static_cast<int>(c.table.parameters.size());  // cycle_s's parameter number
  for (const report::SweepTable::Row& r : c.table.rows) {
    row.bind(1, static_cast<int64_t>(r.point));
    for (size_t p = 0; p < r.values.size(); ++p) row.bind(2 + static_cast<int>(p), r.values[p]);
    if (r.feasible) row.bind(kpis, r.cycleS).bind(kpis + 1, r.energyJ);
    else row.bindNull(kpis).bindNull(kpis + 1);
    row.bind(kpis + 2, r.result);
    if (!row.run()) return "'" + path + "': point " + std::to_string(r.point) + ": " + db.errorText();
  }
  if (!db.exec("COMMIT")) return "'" + path + "': " + db.errorText();
  return "";
}

std::string read(const std::string& path, Contents& c) {
  history::Connection db;
  if (!isSqliteFile(path) || !db.open(path, false)) return "cannot read '" + path + "' as a SQLite database";
  const std::string notASweep = "'" + path + "' is not a sweep database (no table 'sweep' with its 'parameters')";
  history::Statement meta(db, "SELECT key, value FROM sweep ORDER BY key");
  if (!meta.valid()) return notASweep;
  std::string parameters;
  bool hasParameters = false;
  while (meta.step()) {
    c.sweep.emplace_back(meta.columnText(0), meta.columnText(1));
    if (c.sweep.back().first == "parameters") {
      parameters = c.sweep.back().second;
      hasParameters = true;
    }
    if (c.sweep.back().first == "file") c.table.title = c.sweep.back().second;
  }
  if (!hasParameters) return notASweep;
  for (size_t start = 0; start <= parameters.size();) {
    const size_t end = std::min(parameters.find('\n', start), parameters.size());
    c.table.parameters.push_back(parameters.substr(start, end - start));
    start = end + 1;
  }
  history::Statement slices(db, "SELECT slice, slices, points FROM slices ORDER BY slice");
  while (slices.step())
    c.slices.push_back({static_cast<size_t>(slices.columnInt(0)), static_cast<size_t>(slices.columnInt(1)), static_cast<size_t>(slices.columnInt(2))});
  std::string select = "SELECT point";
  for (const std::string& p : c.table.parameters) select += ", " + quoted(p);
  select += ", cycle_s, energy_J, result FROM points ORDER BY point";
  history::Statement rows(db, select.c_str());
  if (!rows.valid()) return "'" + path + "': " + db.errorText();
  const int n = static_cast<int>(c.table.parameters.size());
  while (rows.step()) {
    report::SweepTable::Row r;
    r.point = static_cast<size_t>(rows.columnInt(0));
    for (int p = 0; p < n; ++p) r.values.push_back(rows.columnText(1 + p));
    r.feasible = !rows.columnIsNull(1 + n);
    r.cycleS = rows.columnDouble(1 + n);
    r.energyJ = rows.columnDouble(2 + n);
    r.result = rows.columnText(3 + n);
    c.table.rows.push_back(std::move(r));
  }
  if (!rows.done()) return "'" + path + "': " + db.errorText();
  return "";
}

}  // namespace

report::SweepTable sweepTable(const SweepSpec& spec, const std::vector<SweepRow>& rows) {
  report::SweepTable t;
  t.title = spec.file.filename().string();
  for (const SweepParameter& p : spec.parameters) t.parameters.push_back(p.name);
  for (const SweepRow& r : rows)
    t.rows.push_back({r.point, r.values, r.eval.feasible, static_cast<double>(r.eval.cycleNs) * 1e-9, r.eval.energyJ, r.eval.feasible ? "ok" : r.eval.reason});
  return t;
}

std::string writeSweepDb(const std::string& path, const SweepSpec& spec, const SweepSlice& slice, const std::vector<SweepRow>& rows) {
  Contents c;
  c.table = sweepTable(spec, rows);
  c.sweep = {{"cell", std::filesystem::path(spec.cellFile).filename().string()},
             {"file", c.table.title},
             {"parameters", joinLines(c.table.parameters)},
             {"points", std::to_string(slice.points)},
             {"sampling", spec.random ? "random" : "grid"},
             {"samples", std::to_string(spec.samples)},
             {"seed", std::to_string(spec.seed)}};
  std::ranges::sort(c.sweep);  // as read() returns them, so the merge compares slices' tables as read
  c.slices = {{slice.index, slice.count, rows.size()}};
  return write(path, c);
}

std::string mergeSweepDbs(const std::string& out, const std::vector<std::string>& inputs) {
  Contents merged;
  for (const std::string& in : inputs) {
    Contents c;
    if (std::string problem = read(in, c); !problem.empty()) return problem;
    if (&in == &inputs.front()) {
      merged.sweep = c.sweep;
      merged.table.title = c.table.title;
      merged.table.parameters = c.table.parameters;
    } else if (c.sweep != merged.sweep) {
      return "'" + in + "' holds another sweep than '" + inputs.front() + "' (its table 'sweep' differs)";
    }
    merged.slices.insert(merged.slices.end(), c.slices.begin(), c.slices.end());
    merged.table.rows.insert(merged.table.rows.end(), std::make_move_iterator(c.table.rows.begin()), std::make_move_iterator(c.table.rows.end()));
  }
  std::ranges::stable_sort(merged.table.rows, {}, &report::SweepTable::Row::point);
  for (size_t i = 1; i < merged.table.rows.size(); ++i)
    if (merged.table.rows[i].point == merged.table.rows[i - 1].point)
      return "point " + std::to_string(merged.table.rows[i].point) + " is in more than one file";
  std::ranges::sort(merged.slices, {}, [](const SweepSlice& s) { return std::pair(s.count, s.index); });
  return write(out, merged);
}

std::string readSweepDb(const std::string& path, report::SweepTable& out) {
  Contents c;
  std::string problem = read(path, c);
  out = std::move(c.table);
  return problem;
}

bool isSqliteFile(const std::string& path) {
  char magic[16] = {};
  std::ifstream in(path, std::ios::binary);
  return in.read(magic, sizeof magic) && std::string(magic, sizeof magic) == std::string("SQLite format 3\0", 16);
}

}  // namespace virtcom::optimize

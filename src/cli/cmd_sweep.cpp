// `virtcom sweep SWEEP.yaml`: device and PLC parameters over grids or random samples, one KPI row
// per point (docs/optimise.md "Sweeps") as CSV, a SQLite database and a page of charts; slices for
// a cluster (--shard), joined with --merge, and the Slurm job-array script that runs them
// (--slurm-script); under mpirun the points are spread over the ranks (docs/scaling.md).
#include <algorithm>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

#include "cli/commands.hpp"
#include "cli/common.hpp"
#include "optimize/ranks.hpp"
#include "optimize/sweep.hpp"
#include "optimize/sweep_db.hpp"
#include "report/sweep_chart.hpp"

namespace virtcom::cli {

namespace {

struct SweepOptions {
  std::string file;
  std::string csv;
  std::string sqlite;
  std::string html;
  std::string shard;                // "I/N", 1-based
  std::vector<std::string> merge;   // OUT IN...
  unsigned slurmTasks = 0;
  unsigned jobs = 0;
};

// "I/N" with 1 <= I <= N.
bool parseShard(const std::string& text, size_t& index, size_t& count) {
  const size_t slash = text.find('/');
  if (slash == std::string::npos) return false;
  char* end = nullptr;
  index = std::strtoul(text.c_str(), &end, 10);
  if (end != text.c_str() + slash) return false;
  count = std::strtoul(text.c_str() + slash + 1, &end, 10);
  return *end == 0 && count >= 1 && index >= 1 && index <= count;
}

// Joins shard CSVs (same header) into one table ordered by point; a point twice is an error.
ExitCode mergeCsv(const std::vector<std::string>& files) {
  std::string header;
  std::vector<std::pair<size_t, std::string>> rows;
  for (size_t f = 1; f < files.size(); ++f) {
    std::ifstream in(files[f]);
    std::string line;
    if (!in || !std::getline(in, line)) {
      std::cerr << "error: --merge: cannot read " << files[f] << "\n";
      return ExitCode::InputError;
    }
    if (header.empty()) header = line;
    else if (line != header) {
      std::cerr << "error: --merge: " << files[f] << " has other columns than " << files[1] << " (a slice of another sweep?)\n";
      return ExitCode::InputError;
    }
    while (std::getline(in, line))
      if (!line.empty()) rows.emplace_back(std::strtoul(line.c_str(), nullptr, 10), line);
  }
  std::ranges::stable_sort(rows, {}, &std::pair<size_t, std::string>::first);
  std::string out = header + "\n";
  for (size_t i = 0; i < rows.size(); ++i) {
    if (i > 0 && rows[i].first == rows[i - 1].first) {
      std::cerr << "error: --merge: point " << rows[i].first << " is in more than one file\n";
      return ExitCode::InputError;
    }
    out += rows[i].second + "\n";
  }
  return writeFile(files[0], out) ? ExitCode::Ok : ExitCode::Usage;
}

// Joins shard databases (--sqlite) into one, and draws the merged sweep when asked (--html).
ExitCode mergeDbs(const std::vector<std::string>& files, const std::string& html) {
  const std::vector<std::string> inputs(files.begin() + 1, files.end());
  if (std::string problem = optimize::mergeSweepDbs(files[0], inputs); !problem.empty()) {
    std::cerr << "error: --merge: " << problem << "\n";
    return ExitCode::InputError;
  }
  if (html.empty()) return ExitCode::Ok;
  report::SweepTable table;
  if (std::string problem = optimize::readSweepDb(files[0], table); !problem.empty()) {
    std::cerr << "error: --html: " << problem << "\n";
    return ExitCode::InputError;
  }
  return writeFile(html, report::sweepHtml(table)) ? ExitCode::Ok : ExitCode::Usage;
}

// Databases merge into a database, CSV files into CSV; a mix is refused.
ExitCode merge(const std::vector<std::string>& files, const std::string& html) {
  const size_t databases = static_cast<size_t>(std::count_if(files.begin() + 1, files.end(), optimize::isSqliteFile));
  if (databases == files.size() - 1) return mergeDbs(files, html);
  if (databases != 0) {
    std::cerr << "error: --merge: the inputs mix SQLite databases and CSV files; merge each kind on its own\n";
    return ExitCode::Usage;
  }
  if (!html.empty()) {
    std::cerr << "error: --html with --merge draws a merged database: merge the slices' --sqlite files\n";
    return ExitCode::Usage;
  }
  return mergeCsv(files);
}

// Single-quoted for bash, so paths with spaces or $ reach virtcom as they are.
std::string shellQuoted(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

// A slice's file as a bash word: "sweep.db" with middle "${SLURM_ARRAY_TASK_ID}" becomes
// 'sweep-'${SLURM_ARRAY_TASK_ID}'.db' (middle left unquoted so bash expands or globs it).
std::string sliceWord(const std::string& merged, const std::string& middle) {
  const size_t dot = merged.rfind('.'), slash = merged.rfind('/');
  const bool hasExtension = dot != std::string::npos && dot > 0 && (slash == std::string::npos || dot > slash + 1);
  const std::string stem = hasExtension ? merged.substr(0, dot) : merged, extension = hasExtension ? merged.substr(dot) : "";
  return shellQuoted(stem + "-") + middle + (extension.empty() ? "" : shellQuoted(extension));
}

// Each task writes its slice as CSV (named after --csv, default sweep.csv) or, with --sqlite, as a
// database; the closing comment gives the merge that joins the slices into the single run's file.
std::string slurmScript(const SweepOptions& o) {
  const std::string n = std::to_string(o.slurmTasks);
  const bool database = !o.sqlite.empty();
  const std::string merged = database ? o.sqlite : (o.csv.empty() ? "sweep.csv" : o.csv);
  const std::string merge = "virtcom sweep --merge " + shellQuoted(merged) + " " + sliceWord(merged, "*") +
                            (o.html.empty() ? "" : " --html " + shellQuoted(o.html));
  return "#!/bin/bash\n"
         "# Runs " + o.file + " as a Slurm job array of " + n + " slices (docs/optimise.md \"On a cluster\").\n"
         "# Submit: sbatch sweep.sbatch; when every task is done (or: sbatch --dependency=afterok:JOBID --wrap \"...\"):\n"
         "#   " + merge + "\n"
         "#SBATCH --job-name=virtcom-sweep\n"
         "#SBATCH --array=1-" + n + "\n"
         "#SBATCH --cpus-per-task=1\n"
         "#SBATCH --output=sweep-%a.log\n"
         "virtcom sweep " + shellQuoted(o.file) + " --shard ${SLURM_ARRAY_TASK_ID}/" + n + " --jobs ${SLURM_CPUS_PER_TASK:-1} " +
         (database ? "--sqlite " : "--csv ") + sliceWord(merged, "${SLURM_ARRAY_TASK_ID}") + "\n";
}

ExitCode sweep(const SweepOptions& o) {
  if (!o.merge.empty()) {
    if (o.merge.size() < 2) {
      std::cerr << "error: --merge OUT.csv IN.csv...: at least one input\n";
      return ExitCode::Usage;
    }
    return merge(o.merge, o.html);
  }
  if (o.file.empty()) {
    std::cerr << "error: a sweep file is needed (or --merge)\n";
    return ExitCode::Usage;
  }
  if (o.slurmTasks) {
    if (!o.html.empty() && o.sqlite.empty()) {
      std::cerr << "error: --html with --slurm-script draws the merged slices' databases: add --sqlite FILE\n";
      return ExitCode::Usage;
    }
    std::cout << slurmScript(o);
    return ExitCode::Ok;
  }
  size_t shard = 1, shards = 1;
  if (!o.shard.empty() && !parseShard(o.shard, shard, shards)) {
    std::cerr << "error: --shard: '" << o.shard << "' is not I/N with 1 <= I <= N (e.g. 2/8)\n";
    return ExitCode::Usage;
  }
  const optimize::Ranks ranks;
  if (!ranks.problem().empty()) {
    std::cerr << "error: " << ranks.problem() << "\n";
    return ExitCode::Usage;
  }
  SourceManager sources;
  Diagnostics diags;
  auto spec = optimize::readSweep(o.file, sources, diags);
  std::unique_ptr<optimize::Sweeper> sweeper;
  if (spec) sweeper = optimize::Sweeper::create(*spec, sources, diags);
  if (ranks.leader()) std::cerr << diags.render(sources);
  if (!sweeper) return ExitCode::InputError;
  const auto points = optimize::sweepPoints(*spec);
  std::vector<size_t> mine;  // this slice: every shards-th point
  for (size_t p = shard - 1; p < points.size(); p += shards) mine.push_back(p);
  const unsigned threads = o.jobs ? o.jobs : ranks.size() > 1 ? 1u : std::max(1u, std::thread::hardware_concurrency());
  const std::vector<optimize::Evaluation> evals =
      ranks.evaluateAll(mine.size(), threads, [&](size_t i) { return sweeper->evaluate(mine[i], points[mine[i]]).eval; });
  if (!ranks.leader()) return ExitCode::Ok;
  std::vector<optimize::SweepRow> rows;
  for (size_t i = 0; i < mine.size(); ++i) rows.push_back({mine[i], sweeper->values(points[mine[i]]), evals[i]});
  const std::string csv = optimize::sweepCsv(*spec, rows);
  if (!o.csv.empty() && !writeFile(o.csv, csv)) return ExitCode::Usage;
  if (o.csv.empty() && o.sqlite.empty() && o.html.empty()) std::cout << csv;
  if (!o.sqlite.empty())
    if (std::string problem = optimize::writeSweepDb(o.sqlite, *spec, {shard, shards, points.size()}, rows); !problem.empty()) {
      std::cerr << "error: --sqlite: " << problem << "\n";
      return ExitCode::Usage;
    }
  if (!o.html.empty() && !writeFile(o.html, report::sweepHtml(optimize::sweepTable(*spec, rows)))) return ExitCode::Usage;
  std::cerr << "sweep: " << rows.size() << " of " << points.size() << " points (slice " << shard << "/" << shards << ")"
            << (ranks.size() > 1 ? " on " + std::to_string(ranks.size()) + " MPI ranks" : std::string()) << "\n";
  return ExitCode::Ok;
}

}  // namespace

void addSweepCommand(CLI::App& app, std::function<void(ExitCode)> setExit) {
  auto o = std::make_shared<SweepOptions>();
  CLI::App* cmd = app.add_subcommand("sweep", "Run a cell over a grid or random sample of device and PLC parameters, one KPI row per point "
                                              "(docs/optimise.md \"Sweeps\")");
  cmd->add_option("sweep", o->file, "the sweep file (YAML): cell, parameters and their values, sampling")->check(CLI::ExistingFile);
  cmd->add_option("--csv", o->csv, "write the rows to this CSV file (default: stdout, unless --sqlite or --html)");
  cmd->add_option("--shard", o->shard, "run only slice I of N (points I-1, I-1+N, ...), e.g. 2/8, for a cluster job array");
  cmd->add_option("--merge", o->merge, "OUT IN...: join the slices' CSV files (or --sqlite databases) into one table ordered by point")->expected(2, 1 << 20);
  cmd->add_option("--slurm-script", o->slurmTasks, "print a Slurm sbatch script running the sweep as a job array of this many slices, each writing its slice of --csv (default sweep.csv) or --sqlite")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--jobs", o->jobs, "points simulated in parallel (default: every core; under mpirun one per rank); never changes the rows")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--sqlite", o->sqlite, "also write the rows to this SQLite database: tables points, sweep, slices (docs/optimise.md)");
  cmd->add_option("--html", o->html, "also write a page charting each KPI over the parameters (with --merge: of the merged database)");
  cmd->callback([o, setExit] { setExit(sweep(*o)); });
}

}  // namespace virtcom::cli

// Collecting scenario cases and running them in parallel.
#include "scenario/suite.hpp"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <filesystem>
#include <mutex>
#include <optional>
#include <thread>

#include "scenario/scenario_file.hpp"

namespace virtcom::scenario {

namespace fs = std::filesystem;

bool globMatches(std::string_view pattern, std::string_view text) {
  // Iterative matching with one backtrack point (the last `*`): linear in practice.
  size_t p = 0, t = 0, starP = std::string_view::npos, starT = 0;
  while (t < text.size()) {
    if (p < pattern.size() && (pattern[p] == '?' || pattern[p] == text[t])) {
      ++p;
      ++t;
    } else if (p < pattern.size() && pattern[p] == '*') {
      starP = p++;
      starT = t;
    } else if (starP != std::string_view::npos) {
      p = starP + 1;
      t = ++starT;
    } else {
      return false;
    }
  }
  while (p < pattern.size() && pattern[p] == '*') ++p;
  return p == pattern.size();
}

namespace {

bool isScenarioFile(const fs::path& p) { return p.extension() == ".yaml" || p.extension() == ".yml"; }

std::string classnameOf(const fs::path& file) {
  std::string name = file.lexically_normal().replace_extension().generic_string();
  while (name.starts_with("./") || name.starts_with("../")) name.erase(0, name.find('/') + 1);
  std::replace(name.begin(), name.end(), '/', '.');
  return name;
}

void addCases(const fs::path& file, const std::string& filter, std::vector<CaseSpec>& out) {
  SourceManager sources;
  Diagnostics diags;
  ScenarioFile parsed;
  const bool readable = readScenarioFile(file.string(), sources, diags, parsed);
  const size_t rows = readable && !parsed.rows.empty() ? parsed.rows.size() : 1;
  for (size_t row = 0; row < rows; ++row) {
    CaseSpec spec{file.string(), readable && !parsed.rows.empty() ? row : SIZE_MAX, "", classnameOf(file)};
    spec.name = readable ? caseName(parsed, spec.row) : file.stem().string();
    if (filter.empty() || globMatches(filter, spec.name) || globMatches(filter, spec.file)) out.push_back(std::move(spec));
  }
}

}  // namespace

std::vector<CaseSpec> collectCases(const std::vector<std::string>& paths, const std::string& filter, std::string& error) {
  std::vector<CaseSpec> cases;
  for (const std::string& path : paths) {
    std::error_code ec;
    if (fs::is_regular_file(path, ec)) {
      addCases(path, filter, cases);
      continue;
    }
    if (!fs::is_directory(path, ec)) {
      error = "'" + path + "' is neither a scenario file nor a directory";
      return {};
    }
    std::vector<fs::path> files;
    for (const auto& entry : fs::recursive_directory_iterator(path, ec))
      if (entry.is_regular_file() && isScenarioFile(entry.path())) files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    for (const fs::path& file : files) addCases(file, filter, cases);
  }
  return cases;
}

void runCases(const std::vector<CaseSpec>& cases, unsigned jobs, const CaseOptions& options,
              const std::function<void(CaseResult& result)>& done) {
  std::vector<std::optional<CaseResult>> results(cases.size());
  std::mutex mutex;
  std::condition_variable finished;
  std::atomic<size_t> next{0};
  auto work = [&] {
    for (size_t i; (i = next.fetch_add(1)) < cases.size();) {
      CaseResult r = runCase(cases[i], options);
      std::lock_guard lock(mutex);
      results[i] = std::move(r);
      finished.notify_one();
    }
  };
  std::vector<std::thread> workers;
  const unsigned threads = std::clamp<unsigned>(jobs, 1, static_cast<unsigned>(std::max<size_t>(cases.size(), 1)));
  for (unsigned t = 0; t < threads; ++t) workers.emplace_back(work);
  for (size_t i = 0; i < cases.size(); ++i) {
    std::unique_lock lock(mutex);
    finished.wait(lock, [&] { return results[i].has_value(); });
    CaseResult r = std::move(*results[i]);
    results[i].reset();
    lock.unlock();
    done(r);
  }
  for (std::thread& w : workers) w.join();
}

}  // namespace virtcom::scenario

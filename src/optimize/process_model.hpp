#pragma once
// The process model `virtcom optimise` searches (docs/optimise.md): the cell's work as operations
// (a device and the procedure/program/position code the PLC's job list gives it, or alternatives
// among several), precedence constraints, shared resources, the objective, the sequences the user
// wrote, and how a candidate becomes the PLC's job list. Read from its own YAML file, every
// mistake reported at its file:line:col (code C070), all in one pass. The model knows nothing
// about search methods (optimize/search.hpp) or simulation (optimize/evaluator.hpp).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/diagnostics.hpp"
#include "core/source.hpp"

namespace virtcom::optimize {

// One way to do an operation: the job the PLC's list holds for it.
struct Alternative {
  std::string name;        // as `choose:` names it: its `name`, or "DEVICE:CODE"
  std::string deviceName;  // a key of the model's `device_numbers:`
  int64_t device = 0;      // the device's number in the job list
  int64_t code = 0;        // procedure / program / position code
};

struct Operation {
  std::string name;
  std::vector<Alternative> alternatives;  // at least one
  bool optional = false;                  // may be left out (`skip`)
  std::vector<uint32_t> after;            // operations that must finish before it starts
  SourceLocation loc;
};

// Operations of different devices that must not work at the same time (a shared workspace): the
// one listed later waits for the one listed earlier.
struct Resource {
  std::string name;
  std::vector<uint32_t> users;
};

// How a candidate's jobs wait for each other. Needed: for what precedence and resources demand
// (the optimiser's rule). Serial: every job for the one before it (a strictly sequential list).
enum class WaitRule { Needed, Serial };

inline constexpr int kSkipped = -1;

// One candidate: an order of all operations (a skipped one keeps a place but yields no job) and
// per operation the alternative chosen (kSkipped: left out).
struct Candidate {
  std::vector<uint32_t> order;
  std::vector<int> choice;
  WaitRule waits = WaitRule::Needed;
  bool ignoreResources = false;  // the resources add no waits (to reproduce a colliding list)
};

struct UserSequence {
  std::string name;
  Candidate candidate;
  SourceLocation loc;
};

// Where a job list goes in the PLC: an ARRAY OF a struct whose fields hold the device number, the
// code and the waits (1-based indices into the list, 0 = none).
struct JobListBinding {
  std::string variable;                 // "MAIN.jobs"
  std::string deviceField = "device";
  std::string codeField = "code";
  std::vector<std::string> waitFields;  // "after1", "after2", ...
  std::string count;                    // optional INT variable given the number of jobs
  std::string progress;                 // optional: jobs finished so far (deadlock reasons)
  std::vector<std::pair<std::string, std::string>> presets;  // `set:` NAME: VALUE, before the first scan
  SourceLocation loc;                   // the `job_list:` section (errors found against the PLC)
};

enum class Objective { Time, Energy, Both };
const char* objectiveName(Objective o);

struct ProcessModel {
  std::filesystem::path file;
  std::string cellFile;                 // resolved against the model file's folder
  JobListBinding jobList;
  std::vector<std::pair<std::string, int64_t>> devices;  // name -> number in the job list
  std::vector<Operation> operations;
  std::vector<Resource> resources;
  std::vector<UserSequence> sequences;
  Objective objective = Objective::Time;
  int64_t timeLimitNs = 0;              // 0: the cell's run.time_limit
  // precedes[a][b]: a must finish before b starts, directly or through other operations
  // (skipped ones included); computed by the reader.
  std::vector<std::vector<char>> precedes;

  int operationIndex(const std::string& name) const;  // -1 if none
};

// Reads and checks `path`. Null with diagnostics on any error.
std::optional<ProcessModel> readProcessModel(const std::string& path, SourceManager& sources, Diagnostics& diags);

// Why `c` is not a valid candidate of `m` (an operation missing or twice, a precedence broken, an
// alternative out of range, a mandatory operation skipped); empty if it is valid.
std::string checkCandidate(const ProcessModel& m, const Candidate& c);

}  // namespace virtcom::optimize

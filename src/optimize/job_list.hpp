#pragma once
// A candidate of the process model as the PLC runs it: the job list (device, code, the jobs each
// waits for), the key that tells two candidates apart only where the PLC would behave differently,
// and the job list as ST text to paste into the program (docs/optimise.md "Job lists").
#include <cstdint>
#include <string>
#include <vector>

#include "optimize/process_model.hpp"

namespace virtcom::optimize {

struct Job {
  uint32_t operation = 0;       // index into ProcessModel::operations
  int64_t device = 0;
  int64_t code = 0;
  std::vector<uint32_t> waits;  // 1-based indices of earlier jobs, ascending
};

struct JobList {
  std::vector<Job> jobs;
  // The PLC behaves the same for two lists with the same key: each device's jobs in the same
  // order, each waiting for the same operations (the PLC steps devices, not list positions).
  std::string key;
};

// The job list of a valid candidate (checkCandidate() is empty). With WaitRule::Needed a job
// waits for the fewest earlier jobs that keep every precedence and resource order: the transitive
// reduction of them together with each device's own list order, which the PLC keeps anyway (a
// job never waits for the previous job of its own device).
JobList buildJobList(const ProcessModel& m, const Candidate& c);

// The job list as an ST initialiser of the binding's array (`[(device := 4, code := 1), ...]`),
// with one comment line per job naming its operation; `arrayType` is the array's declared type
// (e.g. ARRAY[1..48] OF ST_Job) and `name` the variable's name inside its POU.
std::string jobListSt(const ProcessModel& m, const JobList& list, const std::string& name, const std::string& arrayType);

}  // namespace virtcom::optimize

// libFuzzer target for the optimiser's process model (`virtcom optimise PROCESS.yaml`,
// docs/optimise.md): readProcessModel (operations, alternatives, precedence closed transitively,
// resources, objective, the user's sequences, the job-list binding), then every user sequence
// checked with checkCandidate and, when valid, turned into its job list and the list's ST text
// as the optimiser does. The model's `cell:` is only resolved, never read. Finds crashes, leaks
// and UB in the reader and the job-list builder; a rejected model always says why.
#include <cstdint>

#include "fuzz_scratch.hpp"
#include "optimize/job_list.hpp"
#include "optimize/process_model.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  namespace optimize = virtcom::optimize;
  const auto model = virtcom::fuzz::readInput(virtcom::fuzz::kProcessModelInput, data, size, optimize::readProcessModel);
  if (!model) return 0;
  for (const optimize::UserSequence& s : model->sequences) {
    if (!optimize::checkCandidate(*model, s.candidate).empty()) continue;
    const optimize::JobList list = optimize::buildJobList(*model, s.candidate);
    if (optimize::jobListSt(*model, list, "jobs", "ARRAY[1..48] OF ST_Job").empty()) __builtin_trap();
  }
  return 0;
}

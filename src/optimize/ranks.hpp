#pragma once
// Evaluations spread over MPI ranks (`mpirun -n N virtcom optimise|sweep ...`, docs/scaling.md)
// with Open MPI (Debian libopenmpi-dev), no cluster code of our own. Every rank runs the same
// deterministic search or sweep; each batch is split by index (i mod N is rank i's), each rank
// simulates its share on its threads and the evaluations are exchanged (MPI_Allgatherv), so
// every rank holds the whole batch, in order, and takes the same next step: the result is the
// single-process one, bit for bit. Decisions that depend on the wall clock (a time budget) are
// the leader's (rank 0), broadcast. Without mpirun there is one rank. Open MPI is called only
// by the module virtcom-mpi.so (mpi_module.hpp), loaded when a launcher started the process.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "optimize/evaluator.hpp"

namespace virtcom::optimize {

struct MpiCalls;

class Ranks {
 public:
  // Joins MPI when this process was started by mpirun or srun (their environment says so);
  // otherwise one rank. One per process. When it cannot join (the module missing, or virtcom
  // built without MPI), problem() says why and the caller must not go on: each rank would
  // do the whole work and write the same files.
  Ranks();
  ~Ranks();
  Ranks(const Ranks&) = delete;
  Ranks& operator=(const Ranks&) = delete;

  const std::string& problem() const { return problem_; }
  int rank() const { return rank_; }
  int size() const { return size_; }
  // Rank 0: the one that prints and writes files.
  bool leader() const { return rank_ == 0; }

  // evaluate(0..count-1), this rank's share on `threads` threads and the rest from the other
  // ranks; result i belongs to index i on every rank. Collective: every rank calls it alike.
  std::vector<Evaluation> evaluateAll(size_t count, unsigned threads, const std::function<Evaluation(size_t)>& evaluate) const;
  // The leader's `value`, on every rank. Collective.
  bool leaderDecides(bool value) const;

 private:
  int rank_ = 0, size_ = 1;
  const MpiCalls* mpi_ = nullptr;
  bool joined_ = false;  // MPI_Init was called here
  std::string problem_;
};

}  // namespace virtcom::optimize

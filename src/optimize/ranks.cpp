// MPI ranks (Open MPI's C API) when built with it, one rank otherwise.
#include "optimize/ranks.hpp"

#include <cstdlib>
#include <cstring>
#include <string>

#ifdef VIRTCOM_HAVE_MPI
#include <mpi.h>
#endif

namespace virtcom::optimize {

#ifdef VIRTCOM_HAVE_MPI
namespace {

// Whether a launcher started this process as one of several: Open MPI's mpirun, PMIx (srun),
// PMI (MPICH, srun --mpi=pmi2). Plain `virtcom` never initialises MPI (no daemon, no delay).
bool launchedByMpi() {
  for (const char* var : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK"})
    if (std::getenv(var)) return true;
  return false;
}

// An evaluation as bytes: feasible, end, cycle, energy, the reason's length and text.
void pack(const Evaluation& e, std::string& out) {
  const auto put = [&](const void* p, size_t n) { out.append(static_cast<const char*>(p), n); };
  const uint8_t flags[2] = {static_cast<uint8_t>(e.feasible), static_cast<uint8_t>(e.end)};
  const uint32_t length = static_cast<uint32_t>(e.reason.size());
  put(flags, 2);
  put(&e.cycleNs, sizeof e.cycleNs);
  put(&e.energyJ, sizeof e.energyJ);
  put(&length, sizeof length);
  put(e.reason.data(), length);
}

const char* unpack(const char* p, Evaluation& e) {
  e.feasible = p[0] != 0;
  e.end = static_cast<RunEnd>(p[1]);
  p += 2;
  std::memcpy(&e.cycleNs, p, sizeof e.cycleNs);
  p += sizeof e.cycleNs;
  std::memcpy(&e.energyJ, p, sizeof e.energyJ);
  p += sizeof e.energyJ;
  uint32_t length = 0;
  std::memcpy(&length, p, sizeof length);
  p += sizeof length;
  e.reason.assign(p, length);
  return p + length;
}

}  // namespace
#endif

Ranks::Ranks() {
#ifdef VIRTCOM_HAVE_MPI
  if (!launchedByMpi()) return;
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (!initialised) {
    MPI_Init(nullptr, nullptr);
    joined_ = true;
  }
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
#endif
}

Ranks::~Ranks() {
#ifdef VIRTCOM_HAVE_MPI
  if (joined_) MPI_Finalize();
#endif
}

std::vector<Evaluation> Ranks::evaluateAll(size_t count, unsigned threads, const std::function<Evaluation(size_t)>& evaluate) const {
  const size_t ranks = static_cast<size_t>(size_), me = static_cast<size_t>(rank_);
  std::vector<Evaluation> results(count);
  const size_t mine = count / ranks + (me < count % ranks ? 1 : 0);
  parallelFor(mine, threads, [&](size_t k) { results[me + k * ranks] = evaluate(me + k * ranks); });
#ifdef VIRTCOM_HAVE_MPI
  if (ranks == 1) return results;
  std::string bytes;
  for (size_t i = me; i < count; i += ranks) pack(results[i], bytes);
  int length = static_cast<int>(bytes.size());
  std::vector<int> lengths(ranks), offsets(ranks);
  MPI_Allgather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, MPI_COMM_WORLD);
  int total = 0;
  for (size_t r = 0; r < ranks; ++r) {
    offsets[r] = total;
    total += lengths[r];
  }
  std::string all(static_cast<size_t>(total), '\0');
  MPI_Allgatherv(bytes.data(), length, MPI_BYTE, all.data(), lengths.data(), offsets.data(), MPI_BYTE, MPI_COMM_WORLD);
  for (size_t r = 0; r < ranks; ++r) {
    if (r == me) continue;
    const char* p = all.data() + offsets[r];
    for (size_t i = r; i < count; i += ranks) p = unpack(p, results[i]);
  }
#endif
  return results;
}

bool Ranks::leaderDecides(bool value) const {
#ifdef VIRTCOM_HAVE_MPI
  if (size_ > 1) {
    int v = value ? 1 : 0;
    MPI_Bcast(&v, 1, MPI_INT, 0, MPI_COMM_WORLD);
    return v != 0;
  }
#endif
  return value;
}

}  // namespace virtcom::optimize

// MPI ranks through the module virtcom-mpi.so (Open MPI) when built with it, one rank otherwise.
#include "optimize/ranks.hpp"

#include <cstdlib>
#include <cstring>
#include <string>

#ifdef VIRTCOM_HAVE_MPI
#include "core/bundled_module.hpp"
#include "optimize/mpi_module.hpp"
#endif

namespace virtcom::optimize {

namespace {

// Whether a launcher started this process as one of several: Open MPI's mpirun, PMIx (srun),
// PMI (MPICH, srun --mpi=pmi2). Plain `virtcom` never initialises MPI (no daemon, no delay).
bool launchedByMpi() {
  for (const char* var : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK"})
    if (std::getenv(var)) return true;
  return false;
}

#ifdef VIRTCOM_HAVE_MPI

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

#endif
}  // namespace

Ranks::Ranks() {
  if (!launchedByMpi()) return;
#ifdef VIRTCOM_HAVE_MPI
  auto calls = bundledModuleSymbol(kMpiModule, kMpiCallsSymbol);
  if (!calls) {
    problem_ = "started by an MPI launcher, but " + calls.error();
    return;
  }
  mpi_ = reinterpret_cast<GetMpiCalls>(*calls)();
  joined_ = mpi_->join(&rank_, &size_);
#else
  problem_ = "started by an MPI launcher, but this virtcom was built without MPI (Debian libopenmpi-dev): each rank would run the whole work";
#endif
}

Ranks::~Ranks() {
#ifdef VIRTCOM_HAVE_MPI
  if (joined_) mpi_->leave();
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
  const int length = static_cast<int>(bytes.size());
  std::vector<int> lengths(ranks), offsets(ranks);
  mpi_->gatherInts(length, lengths.data());
  int total = 0;
  for (size_t r = 0; r < ranks; ++r) {
    offsets[r] = total;
    total += lengths[r];
  }
  std::string all(static_cast<size_t>(total), '\0');
  mpi_->gatherBytes(bytes.data(), length, all.data(), lengths.data(), offsets.data());
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
  if (size_ > 1) return mpi_->broadcastInt(value ? 1 : 0) != 0;
#endif
  return value;
}

}  // namespace virtcom::optimize

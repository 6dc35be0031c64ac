// virtcom-mpi.so: Open MPI's C API behind optimize::MpiCalls (mpi_module.hpp says why a module).
#include <mpi.h>

#include "optimize/mpi_module.hpp"

namespace {

using virtcom::optimize::MpiCalls;

bool join(int* rank, int* size) {
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (!initialised) MPI_Init(nullptr, nullptr);
  MPI_Comm_rank(MPI_COMM_WORLD, rank);
  MPI_Comm_size(MPI_COMM_WORLD, size);
  return !initialised;
}

void leave() { MPI_Finalize(); }

void gatherInts(int value, int* values) { MPI_Allgather(&value, 1, MPI_INT, values, 1, MPI_INT, MPI_COMM_WORLD); }

void gatherBytes(const char* mine, int length, char* all, const int* lengths, const int* offsets) {
  MPI_Allgatherv(mine, length, MPI_BYTE, all, lengths, offsets, MPI_BYTE, MPI_COMM_WORLD);
}

int broadcastInt(int value) {
  MPI_Bcast(&value, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return value;
}

constexpr MpiCalls kCalls{join, leave, gatherInts, gatherBytes, broadcastInt};

}  // namespace

extern "C" [[gnu::visibility("default")]] const MpiCalls* virtcomMpiCalls() { return &kCalls; }

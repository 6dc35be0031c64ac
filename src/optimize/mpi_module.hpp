#pragma once
// The interface between optimize::Ranks (ranks.cpp, in the executable) and the module
// virtcom-mpi.so (mpi_module.cpp), the only code that calls Open MPI. Linked into the executable,
// Open MPI's libraries (libmpi, libopen-pal, hwloc, libevent, ...) were loaded and relocated by
// every command; as a module they are loaded only by a process that mpirun or srun started
// (core/bundled_module.hpp, docs/performance.md "Start-up").
// Header-only on purpose: the module needs no symbol of the executable.

namespace virtcom::optimize {

// The few collectives Ranks needs, on MPI_COMM_WORLD.
struct MpiCalls {
  // MPI_Init unless MPI is already initialised; this process's rank and the world's size.
  // Returns whether MPI_Init was called here (then `leave` must be called once at the end).
  bool (*join)(int* rank, int* size);
  void (*leave)();
  // MPI_Allgather of one int: values[r] is rank r's `value` (values has size() entries).
  void (*gatherInts)(int value, int* values);
  // MPI_Allgatherv of bytes: rank r's `length` bytes land at all + offsets[r].
  void (*gatherBytes)(const char* mine, int length, char* all, const int* lengths, const int* offsets);
  // MPI_Bcast of rank 0's `value`.
  int (*broadcastInt)(int value);
};

// The module's one function (extern "C", found by name).
using GetMpiCalls = const MpiCalls* (*)();
inline constexpr const char* kMpiModule = "virtcom-mpi.so";
inline constexpr const char* kMpiCallsSymbol = "virtcomMpiCalls";

}  // namespace virtcom::optimize

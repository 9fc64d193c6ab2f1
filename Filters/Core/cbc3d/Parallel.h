#ifndef cbc3d_Parallel_h
#define cbc3d_Parallel_h

#include <cstddef>

namespace cbc3d
{
/// Number of threads to use for a request: 0 means the OpenMP default (all cores).
int ThreadCount(int requested);

/// The calling thread's id inside a parallel region (0 outside one).
int ThreadId();

/// Physical memory of this machine in bytes (0 if unknown).
std::size_t PhysicalMemoryBytes();
} // namespace cbc3d

#endif

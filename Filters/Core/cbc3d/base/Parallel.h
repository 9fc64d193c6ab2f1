#ifndef cbc3d_Parallel_h
#define cbc3d_Parallel_h

#include <atomic>
#include <cstddef>
#include <exception>

namespace cbc3d
{
/// Number of threads to use for a request: 0 means the OpenMP default (all cores).
int ThreadCount(int requested);

/// Starts the OpenMP runtime's threads for a request now, while memory is plentiful: libgomp
/// ends the process with its own message when it cannot create a thread later. Returns false,
/// having started none, when the threads cannot all be created (address space too small for
/// their stacks), so that the caller can say so.
bool StartThreads(int requested);

/// The calling thread's id inside a parallel region (0 outside one).
int ThreadId();

/// Physical memory of this machine in bytes (0 if unknown).
std::size_t PhysicalMemoryBytes();

/// The most threads a request may ask for: more only exhausts the OpenMP runtime's stacks.
constexpr int MaximumThreads = 1024;

/// Carries an exception (std::bad_alloc, typically) out of an OpenMP parallel region, which it
/// may not leave by itself (that calls std::terminate): each thread runs its work through Run,
/// which keeps the first exception and, once one is kept, runs no more work (its results would be
/// thrown away); after the region, Rethrow throws it on the calling thread. Work passed to Run
/// must not hold a worksharing construct or a barrier, which every thread has to meet.
class RegionErrors
{
public:
  template <typename Work>
  void Run(Work&& work) noexcept
  {
    if (this->Failed())
      return;
    try
    {
      work();
    }
    catch (...)
    {
      this->Keep(std::current_exception());
    }
  }
  bool Failed() const { return this->Flag.load(std::memory_order_relaxed); }
  void Rethrow() const;

private:
  void Keep(std::exception_ptr error) noexcept;
  std::exception_ptr First;
  std::atomic<bool> Flag{ false };
};
} // namespace cbc3d

#endif

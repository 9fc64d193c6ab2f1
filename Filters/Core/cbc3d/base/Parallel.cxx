#include "cbc3d/base/Parallel.h"

#include <omp.h>

#include <algorithm>
#include <condition_variable>
#include <mutex>
#include <system_error>
#include <thread>
#include <unistd.h>
#include <vector>

namespace cbc3d
{
int ThreadCount(int requested)
{
  return requested > 0 ? std::min(requested, MaximumThreads) : omp_get_max_threads();
}

namespace
{
// Whether `count` threads with the default stack (libgomp's too, unless OMP_STACKSIZE says
// otherwise) can exist at once. Their stacks stay in glibc's cache for libgomp to reuse.
bool CanCreateThreads(int count)
{
  std::mutex mutex;
  std::condition_variable released;
  bool release = false;
  std::vector<std::thread> threads;
  bool created = true;
  try
  {
    threads.reserve(count);
    for (int i = 0; i < count; ++i)
    {
      threads.emplace_back([&] {
        std::unique_lock<std::mutex> lock(mutex);
        released.wait(lock, [&] { return release; });
      });
    }
  }
  catch (const std::system_error&)
  {
    created = false;
  }
  {
    std::lock_guard<std::mutex> lock(mutex);
    release = true;
  }
  released.notify_all();
  for (std::thread& thread : threads)
  {
    thread.join();
  }
  return created;
}
} // namespace

bool StartThreads(int requested)
{
  const int count = ThreadCount(requested);
  if (!CanCreateThreads(count - 1))
  {
    return false;
  }
#pragma omp parallel num_threads(count)
  {
    static_cast<void>(omp_get_thread_num());
  }
  return true;
}

int ThreadId()
{
  return omp_get_thread_num();
}

std::size_t PhysicalMemoryBytes()
{
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long pageSize = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && pageSize > 0 ? static_cast<std::size_t>(pages) * pageSize : 0;
}

void RegionErrors::Keep(std::exception_ptr error) noexcept
{
  bool expected = false;
  if (this->Flag.compare_exchange_strong(expected, true))
  {
    this->First = error; // only the first thread gets here
  }
}

void RegionErrors::Rethrow() const
{
  if (this->Failed())
  {
    std::rethrow_exception(this->First);
  }
}
} // namespace cbc3d

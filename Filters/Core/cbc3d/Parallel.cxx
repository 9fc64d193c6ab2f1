#include "cbc3d/Parallel.h"

#include <omp.h>

#include <algorithm>
#include <unistd.h>

namespace cbc3d
{
int ThreadCount(int requested)
{
  return requested > 0 ? std::min(requested, MaximumThreads) : omp_get_max_threads();
}

void StartThreads(int requested)
{
#pragma omp parallel num_threads(ThreadCount(requested))
  {
    static_cast<void>(omp_get_thread_num());
  }
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

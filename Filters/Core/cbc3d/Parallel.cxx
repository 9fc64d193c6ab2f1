#include "cbc3d/Parallel.h"

#include <omp.h>
#include <unistd.h>

namespace cbc3d
{
int ThreadCount(int requested)
{
  return requested > 0 ? requested : omp_get_max_threads();
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
} // namespace cbc3d

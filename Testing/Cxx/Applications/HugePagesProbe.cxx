// A small program for UnitTestHugePages: says each time it starts, runs itself again with huge
// pages asked of malloc as cbc3d does, then reports the tunables it runs with and the huge pages
// the kernel gave a 64 MiB block it wrote.
#include "HugePages.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

namespace
{
// AnonHugePages of this process in kB (-1 where /proc says nothing).
long AnonHugePagesKiB()
{
  std::ifstream rollup("/proc/self/smaps_rollup");
  std::string line;
  while (std::getline(rollup, line))
  {
    long value = 0;
    if (std::sscanf(line.c_str(), "AnonHugePages: %ld", &value) == 1)
      return value;
  }
  return -1;
}
} // namespace

int main(int, char* argv[])
{
  std::printf("start\n");
  std::fflush(stdout); // an exec drops what is still buffered
  RunAgainWithHugePages(argv);
  const std::size_t bytes = std::size_t(64) << 20;
  char* block = static_cast<char*>(std::malloc(bytes));
  if (!block)
    return 1;
  std::memset(block, 1, bytes);
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  std::printf("tunables %s\nhuge_kib %ld\nsum %d\n", tunables ? tunables : "(none)", AnonHugePagesKiB(),
    int(block[bytes / 2] + block[bytes - 1]));
  std::free(block);
  return 0;
}

// A small program for UnitTestHugePages: says each time it starts. Started without arguments it
// is the launcher: it starts itself again with huge pages asked of malloc, as cbc3d's launcher
// starts the mesher (holding SIGUSR1). Started again ("started"), it reports whether SIGUSR1
// came blocked, whether one raised before ReleaseHeldSignals waited for it, the tunables it
// runs with and the huge pages the kernel gave a 64 MiB block it wrote. With "missing" it tries
// to start a program that is not there and reports what it was left with.
#include "HugePages.h"

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

namespace
{
volatile std::sig_atomic_t Caught = 0;

void OnUser1(int)
{
  Caught = 1;
}

bool User1Blocked()
{
  sigset_t mask;
  sigprocmask(SIG_BLOCK, nullptr, &mask);
  return sigismember(&mask, SIGUSR1) == 1;
}

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

// Reports what a failed start leaves: errno, the tunables, the mask, the variable.
int ReportFailedStart(char* argv[])
{
  RunWithHugePages("/nonexistent/cbc3d-probe", argv, { SIGUSR1 });
  const int failure = errno;
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  std::printf("enoent %d\ntunables %s\nusr1_blocked %d\nheld_variable %s\n", int(failure == ENOENT),
    tunables ? tunables : "(none)", int(User1Blocked()),
    std::getenv("CBC3D_HELD_SIGNALS") ? "set" : "unset");
  return 0;
}
} // namespace

int main(int argc, char* argv[])
{
  std::printf("start\n");
  std::fflush(stdout); // an exec drops what is still buffered
  if (argc > 1 && std::strcmp(argv[1], "missing") == 0)
    return ReportFailedStart(argv);
  if (argc == 1)
  {
    char started[] = "started";
    char* again[] = { argv[0], started, nullptr };
    RunWithHugePages("/proc/self/exe", again, { SIGUSR1 });
    std::printf("exec_failed\n");
    return 1;
  }
  std::printf("usr1_blocked %d\n", int(User1Blocked()));
  std::signal(SIGUSR1, OnUser1);
  std::raise(SIGUSR1);
  std::printf("caught_before_release %d\n", int(Caught));
  ReleaseHeldSignals();
  std::printf("caught_after_release %d\nusr1_blocked_after %d\nheld_variable %s\n", int(Caught),
    int(User1Blocked()), std::getenv("CBC3D_HELD_SIGNALS") ? "set" : "unset");
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

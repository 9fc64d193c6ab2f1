#include "HugePages.h"

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <string>
#include <unistd.h>

// Every new array of a run is faulted in a 4 KiB page at a time, several microseconds a fault on
// a virtual machine: an eighth of the brain's run, and more than a quarter of a 471 M voxel
// image's. With huge pages (2 MiB, where the kernel allows them for memory that asks: its
// default "madvise" mode) the faults drop 7 to 60 times. Where the kernel gives none, nothing
// changes. The cbc3d command is a small launcher (Launcher.cxx) that starts the mesher this
// way: glibc reads the tunable only at a process's start, and a mesher that ran itself again
// would load VTK twice.
namespace
{
// The signals RunWithHugePages blocked, for the process it runs: "2,15,1".
constexpr const char* HeldVariable = "CBC3D_HELD_SIGNALS";
} // namespace

void RunWithHugePages(const char* program, char* argv[], const std::vector<int>& held)
{
  constexpr const char* Tunable = "glibc.malloc.hugetlb";
  const char* found = std::getenv("GLIBC_TUNABLES");
  const bool had = found != nullptr;
  const std::string current = had ? found : "";
  if (current.find(Tunable) == std::string::npos) // the user's choice stands, "0" included
  {
    std::string value = current.empty() ? std::string() : current + ":";
    value += std::string(Tunable) + "=1";
    setenv("GLIBC_TUNABLES", value.c_str(), 1);
  }
  sigset_t hold, before;
  sigemptyset(&hold);
  for (const int signal : held)
    sigaddset(&hold, signal);
  sigprocmask(SIG_BLOCK, &hold, &before);
  std::string blocked; // only those not blocked already: the new program unblocks them
  for (const int signal : held)
    if (!sigismember(&before, signal))
      blocked += (blocked.empty() ? "" : ",") + std::to_string(signal);
  setenv(HeldVariable, blocked.c_str(), 1);
  execv(program, argv);
  const int failure = errno;
  unsetenv(HeldVariable);
  sigprocmask(SIG_SETMASK, &before, nullptr);
  if (had)
    setenv("GLIBC_TUNABLES", current.c_str(), 1);
  else
    unsetenv("GLIBC_TUNABLES");
  errno = failure;
}

void ReleaseHeldSignals()
{
  const char* held = std::getenv(HeldVariable);
  if (!held)
  {
    return;
  }
  sigset_t release;
  sigemptyset(&release);
  for (const char* at = held; *at;)
  {
    char* end = nullptr;
    const long signal = std::strtol(at, &end, 10);
    if (end == at)
      break;
    sigaddset(&release, int(signal));
    at = *end == ',' ? end + 1 : end;
  }
  unsetenv(HeldVariable);
  sigprocmask(SIG_UNBLOCK, &release, nullptr);
}

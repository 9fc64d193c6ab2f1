#include "HugePages.h"

#include <csignal>
#include <cstdlib>
#include <cstring>
#include <string>
#include <unistd.h>

// Every new array of a run is faulted in a 4 KiB page at a time, several microseconds a fault on
// a virtual machine: an eighth of the brain's run, and more than a quarter of a 471 M voxel
// image's. With huge pages (2 MiB, where the kernel allows them for memory that asks: its
// default "madvise" mode) the faults drop 7 to 60 times. Where the kernel gives none, nothing
// changes.
namespace
{
// The signals RunAgainWithHugePages blocked, for the process it runs: "2,15,1".
constexpr const char* HeldVariable = "CBC3D_HELD_SIGNALS";
} // namespace

void RunAgainWithHugePages(char* argv[], const std::vector<int>& held)
{
  constexpr const char* Tunable = "glibc.malloc.hugetlb";
  const char* found = std::getenv("GLIBC_TUNABLES");
  const bool had = found != nullptr;
  const std::string current = had ? found : "";
  if (had && current.find(Tunable) != std::string::npos)
  {
    return; // set by the user (any value, "0" included), or by the first run
  }
  // Under valgrind the new process would run outside it (valgrind follows no exec by default).
  const char* preload = std::getenv("LD_PRELOAD");
  if (preload && std::strstr(preload, "vgpreload"))
  {
    return;
  }
  std::string value = current.empty() ? std::string() : current + ":";
  value += std::string(Tunable) + "=1";
  if (setenv("GLIBC_TUNABLES", value.c_str(), 1) != 0)
  {
    return;
  }
  sigset_t hold, before;
  sigemptyset(&hold);
  for (const int signal : held)
    sigaddset(&hold, signal);
  sigprocmask(SIG_BLOCK, &hold, &before);
  std::string blocked; // only those not blocked already: the new process unblocks them
  for (const int signal : held)
    if (!sigismember(&before, signal))
      blocked += (blocked.empty() ? "" : ",") + std::to_string(signal);
  setenv(HeldVariable, blocked.c_str(), 1);
  execv("/proc/self/exe", argv);
  // Still here: no /proc, or the exec was refused. Run as we are, without the setting.
  unsetenv(HeldVariable);
  sigprocmask(SIG_SETMASK, &before, nullptr);
  if (had)
    setenv("GLIBC_TUNABLES", current.c_str(), 1);
  else
    unsetenv("GLIBC_TUNABLES");
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

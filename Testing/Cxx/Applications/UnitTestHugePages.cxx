// cbc3d runs itself again with glibc's malloc asking for transparent huge pages
// (RunAgainWithHugePages), once, keeping the user's own tunables and choice.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

namespace
{
struct ProbeRun
{
  int Starts = 0;
  std::string Tunables;
  long HugeKiB = -1;
  std::map<std::string, std::string> Said; // the probe's other lines: key -> value
};

// Runs the probe under `environment` (arguments to env(1)) and reads what it printed.
ProbeRun RunProbe(const std::string& environment)
{
  const std::string command = "env " + environment + " " CBC3D_HUGEPAGES_PROBE " 2>/dev/null";
  ProbeRun run;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe)
    return run;
  char line[4096];
  while (std::fgets(line, sizeof(line), pipe))
  {
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "start")
      ++run.Starts;
    else if (key == "tunables")
      words >> run.Tunables;
    else if (key == "huge_kib")
      words >> run.HugeKiB;
    else
      words >> run.Said[key];
  }
  EXPECT_EQ(pclose(pipe), 0) << command;
  return run;
}

// The kernel's transparent huge page mode: "always", "madvise" or "never" ("" if unknown).
std::string HugePageMode()
{
  std::ifstream file("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string word;
  while (file >> word)
    if (word.size() > 2 && word.front() == '[' && word.back() == ']')
      return word.substr(1, word.size() - 2);
  return "";
}
} // namespace

TEST(HugePages, RunsAgainOnceWithTheTunableSet)
{
  const ProbeRun run = RunProbe("-u GLIBC_TUNABLES -u LD_PRELOAD");
  EXPECT_EQ(run.Starts, 2);
  EXPECT_EQ(run.Tunables, "glibc.malloc.hugetlb=1");
  const std::string mode = HugePageMode();
  if (mode == "always" || mode == "madvise")
  {
    // 64 MiB written: at least one 2 MiB page where the kernel has any to give.
    EXPECT_GE(run.HugeKiB, 2048) << "kernel mode " << mode;
  }
}

TEST(HugePages, HoldsStopSignalsUntilTheNewProcessReleasesThem)
{
  // A signal sent while the program starts again waits (blocked across the exec) for the new
  // process's handlers, instead of ending it by default before they are in place.
  ProbeRun run = RunProbe("-u GLIBC_TUNABLES -u LD_PRELOAD");
  ASSERT_EQ(run.Starts, 2);
  EXPECT_EQ(run.Said["usr1_blocked"], "1");
  EXPECT_EQ(run.Said["caught_before_release"], "0");
  EXPECT_EQ(run.Said["caught_after_release"], "1");
  EXPECT_EQ(run.Said["usr1_blocked_after"], "0");
  EXPECT_EQ(run.Said["held_variable"], "unset");
  // Not run again: nothing is held, the signal is handled at once.
  run = RunProbe("-u LD_PRELOAD GLIBC_TUNABLES=glibc.malloc.hugetlb=0");
  ASSERT_EQ(run.Starts, 1);
  EXPECT_EQ(run.Said["usr1_blocked"], "0");
  EXPECT_EQ(run.Said["caught_before_release"], "1");
}

TEST(HugePages, KeepsTheUsersOtherTunables)
{
  const ProbeRun run = RunProbe("-u LD_PRELOAD GLIBC_TUNABLES=glibc.malloc.check=0");
  EXPECT_EQ(run.Starts, 2);
  EXPECT_EQ(run.Tunables, "glibc.malloc.check=0:glibc.malloc.hugetlb=1");
}

TEST(HugePages, LeavesTheUsersChoiceAlone)
{
  const ProbeRun run = RunProbe("-u LD_PRELOAD GLIBC_TUNABLES=glibc.malloc.hugetlb=0");
  EXPECT_EQ(run.Starts, 1);
  EXPECT_EQ(run.Tunables, "glibc.malloc.hugetlb=0");
  if (HugePageMode() == "madvise")
  {
    EXPECT_EQ(run.HugeKiB, 0); // nothing asked, nothing given
  }
}

TEST(HugePages, StaysUnderValgrind)
{
  // Valgrind follows no exec by default: the new process would run outside it.
  const ProbeRun run = RunProbe("-u GLIBC_TUNABLES LD_PRELOAD=/nonexistent/vgpreload_memcheck-amd64-linux.so");
  EXPECT_EQ(run.Starts, 1);
  EXPECT_EQ(run.Tunables, "(none)");
}

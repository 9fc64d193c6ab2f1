// cbc3d's launcher starts the mesher with glibc's malloc asking for transparent huge pages
// (RunWithHugePages), keeping the user's own tunables and choice, and holding stop signals
// until the mesher's handlers are in place.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <sys/wait.h>
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

// Runs the probe under `environment` (arguments to env(1)) with `arguments` and reads what it
// printed.
ProbeRun RunProbe(const std::string& environment, const std::string& arguments = "")
{
  const std::string command =
    "env " + environment + " " CBC3D_HUGEPAGES_PROBE " " + arguments + " 2>/dev/null";
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

TEST(HugePages, StartsTheProgramWithTheTunableSet)
{
  const ProbeRun run = RunProbe("-u GLIBC_TUNABLES");
  EXPECT_EQ(run.Starts, 2);
  EXPECT_EQ(run.Tunables, "glibc.malloc.hugetlb=1");
  const std::string mode = HugePageMode();
  if (mode == "always" || mode == "madvise")
  {
    // 64 MiB written: at least one 2 MiB page where the kernel has any to give.
    EXPECT_GE(run.HugeKiB, 2048) << "kernel mode " << mode;
  }
}

TEST(HugePages, HoldsStopSignalsUntilTheProgramReleasesThem)
{
  // A signal sent while the program starts waits (blocked across the exec) for the program's
  // handlers, instead of ending it by default before they are in place; the same where the
  // user's own tunable is kept.
  for (const char* environment : { "-u GLIBC_TUNABLES", "GLIBC_TUNABLES=glibc.malloc.hugetlb=0" })
  {
    ProbeRun run = RunProbe(environment);
    ASSERT_EQ(run.Starts, 2) << environment;
    EXPECT_EQ(run.Said["usr1_blocked"], "1") << environment;
    EXPECT_EQ(run.Said["caught_before_release"], "0") << environment;
    EXPECT_EQ(run.Said["caught_after_release"], "1") << environment;
    EXPECT_EQ(run.Said["usr1_blocked_after"], "0") << environment;
    EXPECT_EQ(run.Said["held_variable"], "unset") << environment;
  }
}

TEST(HugePages, KeepsTheUsersOtherTunables)
{
  const ProbeRun run = RunProbe("GLIBC_TUNABLES=glibc.malloc.check=0");
  EXPECT_EQ(run.Starts, 2);
  EXPECT_EQ(run.Tunables, "glibc.malloc.check=0:glibc.malloc.hugetlb=1");
}

TEST(HugePages, LeavesTheUsersChoiceAlone)
{
  const ProbeRun run = RunProbe("GLIBC_TUNABLES=glibc.malloc.hugetlb=0");
  EXPECT_EQ(run.Starts, 2);
  EXPECT_EQ(run.Tunables, "glibc.malloc.hugetlb=0");
  if (HugePageMode() == "madvise")
  {
    EXPECT_EQ(run.HugeKiB, 0); // nothing asked, nothing given
  }
}

TEST(HugePages, AFailedStartLeavesTheProcessAsItWas)
{
  ProbeRun run = RunProbe("-u GLIBC_TUNABLES", "missing");
  EXPECT_EQ(run.Starts, 1);
  EXPECT_EQ(run.Said["enoent"], "1");
  EXPECT_EQ(run.Tunables, "(none)");
  EXPECT_EQ(run.Said["usr1_blocked"], "0");
  EXPECT_EQ(run.Said["held_variable"], "unset");
  run = RunProbe("GLIBC_TUNABLES=glibc.malloc.check=0", "missing");
  EXPECT_EQ(run.Tunables, "glibc.malloc.check=0");
}

TEST(Launcher, SaysWhichMesherItCannotStart)
{
  // The cbc3d command alone, without the mesher it starts: one line and exit code 1.
  char folder[] = "/tmp/cbc3d-launcher-XXXXXX";
  ASSERT_NE(mkdtemp(folder), nullptr);
  const std::string copy = std::string(folder) + "/cbc3d";
  ASSERT_EQ(std::system(("cp " CBC3D_CLI " " + copy).c_str()), 0);
  FILE* pipe = popen((copy + " --version 2>&1").c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string said;
  char line[4096];
  while (std::fgets(line, sizeof(line), pipe))
    said += line;
  const int status = pclose(pipe);
  std::system(("rm -rf " + std::string(folder)).c_str());
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 1) << status;
  EXPECT_NE(said.find("cbc3d: error: cannot run the mesher " + std::string(folder)), std::string::npos) << said;
  EXPECT_NE(said.find("libexec/cbc3d/cbc3d: No such file or directory"), std::string::npos) << said;
  EXPECT_EQ(std::count(said.begin(), said.end(), '\n'), 1) << said;
}

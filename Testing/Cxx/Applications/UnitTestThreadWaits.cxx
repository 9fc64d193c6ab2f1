// The launcher gives the mesher short OpenMP waits (ShortenThreadWaits), unless the user chose.
#include "ThreadWaits.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

namespace
{
// The two variables as a test found them, put back when it ends.
class SavedWaitVariables
{
public:
  SavedWaitVariables()
  {
    for (int i = 0; i < 2; ++i)
    {
      const char* value = std::getenv(Names[i]);
      this->Had[i] = value != nullptr;
      this->Values[i] = value ? value : "";
      unsetenv(Names[i]);
    }
  }
  ~SavedWaitVariables()
  {
    for (int i = 0; i < 2; ++i)
    {
      if (this->Had[i])
        setenv(Names[i], this->Values[i].c_str(), 1);
      else
        unsetenv(Names[i]);
    }
  }

private:
  static constexpr const char* Names[2] = { "OMP_WAIT_POLICY", "GOMP_SPINCOUNT" };
  bool Had[2] = { false, false };
  std::string Values[2];
};

std::string Variable(const char* name)
{
  const char* value = std::getenv(name);
  return value ? value : "(unset)";
}
} // namespace

TEST(ThreadWaits, ShortSpinsUnlessTheUserChoseAWait)
{
  const SavedWaitVariables saved;
  // Nothing chosen: the short count.
  EXPECT_TRUE(ShortenThreadWaits());
  EXPECT_EQ(Variable("GOMP_SPINCOUNT"), "1000");
  // A count of the user's own, even 0, stays.
  setenv("GOMP_SPINCOUNT", "0", 1);
  EXPECT_FALSE(ShortenThreadWaits());
  EXPECT_EQ(Variable("GOMP_SPINCOUNT"), "0");
  // So does a wait policy, and no count is added beside it.
  unsetenv("GOMP_SPINCOUNT");
  setenv("OMP_WAIT_POLICY", "active", 1);
  EXPECT_FALSE(ShortenThreadWaits());
  EXPECT_EQ(Variable("GOMP_SPINCOUNT"), "(unset)");
  EXPECT_EQ(Variable("OMP_WAIT_POLICY"), "active");
}

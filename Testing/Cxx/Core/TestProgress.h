#ifndef cbc3d_TestProgress_h
#define cbc3d_TestProgress_h

#include "cbc3d/base/Progress.h"
#include "cbc3d/base/Status.h"

#include <gtest/gtest.h>

#include <functional>
#include <vector>

/// Runs a core function to the end, recording the fraction of every poll; then once per poll
/// with a Progress that asks to stop at that poll only, expecting the run to end Aborted: a
/// stop seen at any poll is honoured, even one the Progress does not repeat. (The closing
/// report of 1.0 comes after the work is done and only reports.) Returns the fractions. Give
/// the function one thread, so that the polls come in the same order every run.
inline std::vector<double> ExpectStopAtEveryPoll(
  const std::function<cbc3d::Status(const cbc3d::Progress&)>& run)
{
  std::vector<double> fractions;
  EXPECT_TRUE(run([&](double fraction) {
    fractions.push_back(fraction);
    return true;
  }).IsOk());
  for (std::size_t stopAt = 0; stopAt < fractions.size(); ++stopAt)
  {
    if (fractions[stopAt] >= 1.0)
    {
      continue;
    }
    std::size_t calls = 0;
    EXPECT_TRUE(run([&](double) { return calls++ != stopAt; }).WasAborted())
      << "a stop at poll " << stopAt << " of " << fractions.size() << " (fraction "
      << fractions[stopAt] << ") was not honoured";
  }
  return fractions;
}

#endif

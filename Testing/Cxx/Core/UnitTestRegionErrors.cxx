// RegionErrors: the first exception of a parallel region reaches the caller, and no work runs
// after it.
#include "cbc3d/base/Parallel.h"

#include <gtest/gtest.h>

#include <atomic>
#include <new>
#include <stdexcept>

TEST(RegionErrors, TheFirstErrorIsThrownAfterTheRegionAndLaterWorkIsSkipped)
{
  cbc3d::RegionErrors errors;
  std::atomic<int> ran(0);
  constexpr int Items = 1000;
#pragma omp parallel for schedule(static, 1) num_threads(4)
  for (int i = 0; i < Items; ++i)
    errors.Run([&] {
      ++ran;
      if (i == 0)
        throw std::length_error("the first");
    });
  EXPECT_THROW(errors.Rethrow(), std::length_error);
  EXPECT_LT(ran.load(), Items); // the threads stopped taking work once it failed

  // Serially: the first error is kept, and nothing runs after it.
  cbc3d::RegionErrors serial;
  int after = 0;
  serial.Run([] { throw std::bad_alloc(); });
  serial.Run([&] { ++after; });
  serial.Run([] { throw std::length_error("a later one"); });
  EXPECT_EQ(after, 0);
  EXPECT_THROW(serial.Rethrow(), std::bad_alloc);

  cbc3d::RegionErrors none;
  none.Run([&] { ++after; });
  EXPECT_EQ(after, 1);
  EXPECT_NO_THROW(none.Rethrow());
}

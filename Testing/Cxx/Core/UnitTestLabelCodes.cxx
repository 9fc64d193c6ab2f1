#include "cbc3d/base/LabelCodes.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>

TEST(LabelCodes, ValuesThatFitIn32BitsAreTheirOwnCodes)
{
  const cbc3d::LabelCodes codes = cbc3d::LabelCodes::ForValues({ 0, 255, -7, INT32_MAX, INT32_MIN });
  EXPECT_TRUE(codes.IsIdentity());
  std::int32_t code = 0;
  EXPECT_TRUE(codes.FindCode(-7, code));
  EXPECT_EQ(code, -7);
  EXPECT_EQ(codes.ValueOf(128), 128);
  EXPECT_FALSE(codes.FindCode(std::int64_t(INT32_MAX) + 1, code)); // no code beyond 32 bits
}

TEST(LabelCodes, LargeValuesGetCodesInTheOrderOfTheirValues)
{
  const std::int64_t big = 5000000000, negative = -5000000000, uint32 = 4000000000;
  const std::int64_t highest = std::numeric_limits<std::int64_t>::max();
  const std::int64_t lowest = std::numeric_limits<std::int64_t>::min();
  const cbc3d::LabelCodes codes =
    cbc3d::LabelCodes::ForValues({ big, 0, uint32, negative, 3, big, highest, lowest, 0 });
  ASSERT_FALSE(codes.IsIdentity());
  const std::int64_t ascending[] = { lowest, negative, 0, 3, uint32, big, highest };
  for (std::int32_t c = 0; c < 7; ++c)
  {
    EXPECT_EQ(codes.ValueOf(c), ascending[c]);
    std::int32_t code = -1;
    ASSERT_TRUE(codes.FindCode(ascending[c], code));
    EXPECT_EQ(code, c);
  }
  std::int32_t code = 0;
  EXPECT_FALSE(codes.FindCode(1, code)); // not a value of the table
  EXPECT_FALSE(codes.FindCode(big + 1, code));
}

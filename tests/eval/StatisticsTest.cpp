// The one median of the reports (engine/eval/Statistics).
#include <gtest/gtest.h>

#include <cmath>

#include "eval/Statistics.hpp"

namespace orthosim {
namespace {

TEST(Statistics, MedianOfOddAndEvenCountsInAnyOrder) {
  EXPECT_EQ(median({3.0}), 3.0);
  EXPECT_EQ(median({5.0, 1.0, 3.0}), 3.0);
  EXPECT_EQ(median({4.0, 1.0, 3.0, 2.0}), 2.5);  // the mean of the two middle values
  EXPECT_EQ(median({2.0, 2.0, 9.0, -1.0}), 2.0);
}

TEST(Statistics, MedianOfNothingIsNotANumber) { EXPECT_TRUE(std::isnan(median({}))); }

}  // namespace
}  // namespace orthosim

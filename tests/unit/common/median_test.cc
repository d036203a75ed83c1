#include "common/estimate/median.h"

#include <gtest/gtest.h>

#include "common/error/check.h"

namespace reenact {
namespace {

TEST(Median, OddCountIsTheMiddleValueWhateverTheOrder) {
  EXPECT_EQ(Median({5, 1, 3}), 3);
  EXPECT_EQ(UpperMedian({5, 1, 3}), 3);
  EXPECT_EQ(Median({7}), 7);
}

TEST(Median, EvenCountAveragesOrTakesTheUpperMiddle) {
  EXPECT_EQ(Median({4, 1, 3, 2}), 2.5);
  EXPECT_EQ(UpperMedian({4, 1, 3, 2}), 3);
  EXPECT_EQ(Median({-1, 1}), 0);
}

TEST(Median, RepeatedValues) {
  EXPECT_EQ(Median({2, 2, 9, 2}), 2);
  EXPECT_EQ(UpperMedian({9, 9, 1, 1}), 9);
}

TEST(Median, EmptySetIsABug) {
  EXPECT_THROW(Median({}), CheckError);
  EXPECT_THROW(UpperMedian({}), CheckError);
}

}  // namespace
}  // namespace reenact

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

TEST(Percentile, NearestRankOfTenValues) {
  // 1..10 shuffled: at least 90 % of them are <= 9, and 9 is the smallest such value.
  const std::vector<double> v = {7, 3, 10, 1, 9, 4, 2, 8, 6, 5};
  EXPECT_EQ(Percentile(v, 0.9), 9);
  EXPECT_EQ(Percentile(v, 0.91), 10);
  EXPECT_EQ(Percentile(v, 0.5), UpperMedian({1, 2, 3, 4, 5, 6, 7, 8, 9}));
  EXPECT_EQ(Percentile(v, 0.0), 1);
  EXPECT_EQ(Percentile(v, 1.0), 10);
}

TEST(Percentile, OneValueIsEveryPercentile) {
  EXPECT_EQ(Percentile({4}, 0.0), 4);
  EXPECT_EQ(Percentile({4}, 0.9), 4);
}

TEST(Percentile, EmptySetOrShareOutsideZeroToOneIsABug) {
  EXPECT_THROW(Percentile({}, 0.9), CheckError);
  EXPECT_THROW(Percentile({1, 2}, 1.5), CheckError);
  EXPECT_THROW(Percentile({1, 2}, -0.1), CheckError);
}

}  // namespace
}  // namespace reenact

#include "core/analysis/order_statistics.h"

#include <gtest/gtest.h>

namespace penumbra {
namespace {

TEST(OrderStatistics, MedianOfOddAndEvenCounts) {
  EXPECT_DOUBLE_EQ(median({3, 1, 2}), 2.0);
  EXPECT_DOUBLE_EQ(median({4, 1, 3, 2}), 2.5);  // not the upper middle value
  EXPECT_DOUBLE_EQ(median({7}), 7.0);
  EXPECT_DOUBLE_EQ(median({2, 2, 9, 2}), 2.0);
  EXPECT_DOUBLE_EQ(median({}), 0.0);
}

TEST(OrderStatistics, NearestRankPercentile) {
  std::vector<double> ten = {10, 9, 8, 7, 6, 5, 4, 3, 2, 1};
  EXPECT_DOUBLE_EQ(percentile(ten, 0.9), 10.0);
  EXPECT_DOUBLE_EQ(percentile(ten, 0.5), 6.0);
  EXPECT_DOUBLE_EQ(percentile(ten, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(percentile(ten, 1.0), 10.0);  // clamped to the last rank
  std::vector<double> hundred;
  for (int i = 1; i <= 100; ++i) hundred.push_back(i);
  EXPECT_DOUBLE_EQ(percentile(hundred, 0.9), 91.0);
  EXPECT_DOUBLE_EQ(percentile({}, 0.9), 0.0);
}

}  // namespace
}  // namespace penumbra

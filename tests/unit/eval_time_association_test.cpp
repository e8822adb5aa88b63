#include "litamin2/eval/time_association.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace le = litamin2::eval;

namespace {

std::vector<double> stamps(int count, double start, double step) {
  std::vector<double> t;
  for (int i = 0; i < count; ++i) t.push_back(start + step * i);
  return t;
}

}  // namespace

TEST(EvalTimeAssociation, KeyframesFindTheirFullRateFrames) {
  const auto full_rate = stamps(100, 10.0, 0.1);  // 10 Hz ground truth
  std::vector<double> keyframes;
  for (int i = 0; i < 100; i += 7) keyframes.push_back(10.0 + 0.1 * i + 0.003);  // 3 ms late
  const auto pairs = le::associate_by_time(full_rate, keyframes, 0.01);
  ASSERT_EQ(pairs.size(), keyframes.size());
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    EXPECT_EQ(pairs[k].query_index, k);
    EXPECT_EQ(pairs[k].reference_index, 7 * k);
  }
}

TEST(EvalTimeAssociation, StampsBeyondTheLimitStayUnpaired) {
  const std::vector<double> reference{0.0, 1.0, 2.0, 3.0};
  const std::vector<double> query{0.02, 1.5, 2.049, 2.07, 9.0};
  const auto pairs = le::associate_by_time(reference, query, 0.05);
  // 1.5 is 0.5 from both neighbours, 2.07 is 0.07 from 2.0, 9.0 is past the end.
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_EQ(pairs[0].reference_index, 0u);
  EXPECT_EQ(pairs[0].query_index, 0u);
  EXPECT_EQ(pairs[1].reference_index, 2u);
  EXPECT_EQ(pairs[1].query_index, 2u);
}

TEST(EvalTimeAssociation, AReferenceStampIsClaimedOnceByTheNearestQuery) {
  const std::vector<double> reference{0.0, 1.0};
  const std::vector<double> query{0.98, 1.01};
  const auto pairs = le::associate_by_time(reference, query, 0.05);
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_EQ(pairs[0].reference_index, 1u);
  EXPECT_EQ(pairs[0].query_index, 1u);  // 0.01 from 1.0 beats 0.02
}

TEST(EvalTimeAssociation, PairsIncreaseInBothIndices) {
  const auto reference = stamps(500, 0.0, 0.1);
  std::vector<double> query;
  for (int i = 0; i < 300; ++i) query.push_back(0.033 * i + 0.001 * (i % 5));  // ~30 Hz, jitter
  const auto pairs = le::associate_by_time(reference, query, 0.02);
  ASSERT_GT(pairs.size(), 50u);
  for (std::size_t k = 1; k < pairs.size(); ++k) {
    EXPECT_GT(pairs[k].reference_index, pairs[k - 1].reference_index);
    EXPECT_GT(pairs[k].query_index, pairs[k - 1].query_index);
  }
  for (const auto& p : pairs) {
    EXPECT_LE(std::abs(reference[p.reference_index] - query[p.query_index]), 0.02);
  }
}

TEST(EvalTimeAssociation, EmptySeriesGiveNoPairs) {
  EXPECT_TRUE(le::associate_by_time({}, {1.0, 2.0}, 0.1).empty());
  EXPECT_TRUE(le::associate_by_time({1.0, 2.0}, {}, 0.1).empty());
}

TEST(EvalTimeAssociation, BadSeriesAndLimitsAreRejected) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(le::time_series_error({0.0, 1.0, 1.0}), "");
  EXPECT_NE(le::time_series_error({0.0, 2.0, 1.0}), "");
  EXPECT_NE(le::time_series_error({0.0, nan}), "");
  EXPECT_EQ(le::time_series_error({0.0, 0.5, 2.0}), "");
  EXPECT_THROW(le::associate_by_time({0.0, 0.0}, {0.0}, 0.1), std::invalid_argument);
  EXPECT_THROW(le::associate_by_time({0.0}, {1.0, 0.5}, 0.1), std::invalid_argument);
  EXPECT_THROW(le::associate_by_time({0.0}, {0.0}, -0.1), std::invalid_argument);
  EXPECT_THROW(le::associate_by_time({0.0}, {0.0}, nan), std::invalid_argument);
}

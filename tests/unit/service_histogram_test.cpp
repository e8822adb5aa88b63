#include "litamin2/service/histogram.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>

namespace litamin2::service {
namespace {

TEST(ServiceHistogram, CountsCumulativelyByUpperBound) {
  Histogram h({1.0, 2.0, 5.0});
  for (double v : {0.5, 1.0, 1.5, 2.0, 4.0, 7.0}) h.observe(v);
  // A value equal to a bound belongs to it (Prometheus's le: less than or equal).
  const std::vector<std::uint64_t> c = h.cumulative_counts();
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c[0], 2u);       // 0.5, 1.0
  EXPECT_EQ(c[1], 4u);       // + 1.5, 2.0
  EXPECT_EQ(c[2], 5u);       // + 4.0
  EXPECT_EQ(h.count(), 6u);  // + 7.0 beyond the last bound (+Inf)
  EXPECT_DOUBLE_EQ(h.sum(), 0.5 + 1.0 + 1.5 + 2.0 + 4.0 + 7.0);
}

TEST(ServiceHistogram, NonFiniteValuesAreNotCounted) {
  Histogram h({1.0});
  h.observe(std::numeric_limits<double>::quiet_NaN());
  h.observe(std::numeric_limits<double>::infinity());
  EXPECT_EQ(h.count(), 0u);
  EXPECT_EQ(h.sum(), 0.0);
}

TEST(ServiceHistogram, RejectsBoundsThatDoNotIncrease) {
  EXPECT_THROW(Histogram({1.0, 1.0}), std::invalid_argument);
  EXPECT_THROW(Histogram({2.0, 1.0}), std::invalid_argument);
  EXPECT_THROW(Histogram({1.0, std::numeric_limits<double>::infinity()}), std::invalid_argument);
  EXPECT_NO_THROW(Histogram{latency_buckets_seconds()});
}

}  // namespace
}  // namespace litamin2::service

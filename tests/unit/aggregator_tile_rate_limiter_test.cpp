// TileRateLimiter: each tile at most once per period, changes within it folded into one
// deferred send, every deferred tile handed out at shutdown.

#include "litamin2/aggregator/tile_rate_limiter.hpp"

#include <gtest/gtest.h>

using namespace litamin2;
using aggregator::TileRateLimiter;
using std::chrono::milliseconds;

namespace {
const mapping::TileKey kA{0, 0}, kB{1, -1};
}

TEST(TileRateLimiter, FirstChangeGoesOutAtOnceLaterOnesWaitForThePeriod) {
  TileRateLimiter limiter(milliseconds(1000));
  const TileRateLimiter::Clock::time_point t0{};
  EXPECT_TRUE(limiter.offer(kA, t0));
  EXPECT_TRUE(limiter.offer(kB, t0 + milliseconds(10)));  // another tile: its own period
  EXPECT_FALSE(limiter.offer(kA, t0 + milliseconds(100)));
  EXPECT_FALSE(limiter.offer(kA, t0 + milliseconds(200)));  // folded into the deferred one
  EXPECT_FALSE(limiter.offer(kA, t0 + milliseconds(300)));
  EXPECT_EQ(limiter.deferred_now(), 1u);
  EXPECT_EQ(limiter.deferred(), 3u);
  EXPECT_EQ(limiter.folded(), 2u);
  EXPECT_TRUE(limiter.take_due(t0 + milliseconds(999)).empty());
  const auto due = limiter.take_due(t0 + milliseconds(1000));
  ASSERT_EQ(due.size(), 1u);  // once, however often it changed
  EXPECT_EQ(due[0], kA);
  EXPECT_EQ(limiter.deferred_now(), 0u);
  // Sent at 1000: the next change waits until 2000.
  EXPECT_FALSE(limiter.offer(kA, t0 + milliseconds(1500)));
  EXPECT_TRUE(limiter.take_due(t0 + milliseconds(1999)).empty());
  EXPECT_EQ(limiter.take_due(t0 + milliseconds(2000)).size(), 1u);
  // A change a period after the last send goes out at once.
  EXPECT_TRUE(limiter.offer(kA, t0 + milliseconds(3000)));
  EXPECT_TRUE(limiter.offer(kB, t0 + milliseconds(3000)));
}

TEST(TileRateLimiter, ZeroPeriodSendsEveryChange) {
  TileRateLimiter limiter(milliseconds(0));
  const TileRateLimiter::Clock::time_point t0{};
  for (int i = 0; i < 5; ++i) EXPECT_TRUE(limiter.offer(kA, t0));
  EXPECT_EQ(limiter.deferred(), 0u);
}

TEST(TileRateLimiter, TakeAllHandsOutEveryDeferredTile) {
  TileRateLimiter limiter(milliseconds(1000));
  const TileRateLimiter::Clock::time_point t0{};
  limiter.offer(kA, t0);
  limiter.offer(kB, t0);
  limiter.offer(kA, t0 + milliseconds(1));
  limiter.offer(kB, t0 + milliseconds(2));
  const auto all = limiter.take_all(t0 + milliseconds(3));
  EXPECT_EQ(all.size(), 2u);
  EXPECT_EQ(limiter.deferred_now(), 0u);
  EXPECT_TRUE(limiter.take_due(t0 + milliseconds(5000)).empty());
}

TEST(TileRateLimiter, NegativePeriodIsRefused) {
  EXPECT_THROW(TileRateLimiter(milliseconds(-1)), std::invalid_argument);
}

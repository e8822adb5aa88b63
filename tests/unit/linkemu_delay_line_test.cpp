// The test link emulator's delay line (tests/link_emulator/delay_line.hpp) and its profile
// validation: frames leave no earlier than their delay, in order without jitter, within the
// jitter's bounds with it, and every frame is counted as forwarded, lost, dropped or queued.
#include "link_emulator/delay_line.hpp"
#include "link_emulator/link_profile.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace {

using litamin2::testing::DelayLine;
using litamin2::testing::LinkProfile;
using std::chrono::milliseconds;
using std::chrono::nanoseconds;

DelayLine::Frame frame_of(std::uint32_t id, std::size_t size = 64) {
  DelayLine::Frame f(size, 0);
  for (int i = 0; i < 4; ++i) f[i] = static_cast<std::uint8_t>(id >> (8 * i));
  return f;
}

std::uint32_t id_of(const DelayLine::Frame& f) {
  std::uint32_t id = 0;
  for (int i = 0; i < 4; ++i) id |= static_cast<std::uint32_t>(f[i]) << (8 * i);
  return id;
}

LinkProfile delayed(milliseconds delay) {
  LinkProfile p;
  p.delay = delay;
  return p;
}

TEST(LinkProfile, ValidProfilesPass) {
  EXPECT_EQ(validate(LinkProfile{}), "");
  LinkProfile p = delayed(milliseconds(100));
  p.jitter = milliseconds(100);
  p.loss_fraction = 1.0;
  EXPECT_EQ(validate(p), "");
}

TEST(LinkProfile, InvalidProfilesAreRejected) {
  LinkProfile negative_delay = delayed(milliseconds(-1));
  EXPECT_NE(validate(negative_delay), "");
  LinkProfile jitter_above_delay = delayed(milliseconds(10));
  jitter_above_delay.jitter = milliseconds(11);
  EXPECT_NE(validate(jitter_above_delay), "");
  LinkProfile negative_jitter = delayed(milliseconds(10));
  negative_jitter.jitter = milliseconds(-1);
  EXPECT_NE(validate(negative_jitter), "");
  for (double loss : {-0.01, 1.01, std::nan("")}) {
    LinkProfile p;
    p.loss_fraction = loss;
    EXPECT_NE(validate(p), "") << loss;
  }
  LinkProfile no_queue;
  no_queue.queue_limit_frames = 0;
  EXPECT_NE(validate(no_queue), "");
  EXPECT_THROW(DelayLine{no_queue}, std::invalid_argument);
}

TEST(DelayLine, ReleasesAFrameExactlyAfterTheDelay) {
  DelayLine line(delayed(milliseconds(100)));
  const auto t0 = DelayLine::Clock::time_point{} + std::chrono::seconds(5);
  EXPECT_EQ(line.push(frame_of(7, 1500), t0), DelayLine::Admission::queued);
  ASSERT_TRUE(line.next_release().has_value());
  EXPECT_EQ(*line.next_release(), t0 + milliseconds(100));
  DelayLine::Frame out;
  EXPECT_FALSE(line.pop_due(t0 + milliseconds(100) - nanoseconds(1), out));
  ASSERT_TRUE(line.pop_due(t0 + milliseconds(100), out));
  EXPECT_EQ(id_of(out), 7u);
  EXPECT_EQ(out.size(), 1500u);
  EXPECT_FALSE(line.pop_due(t0 + milliseconds(200), out));
  EXPECT_FALSE(line.next_release().has_value());
  EXPECT_EQ(line.counters().forwarded, 1u);
  EXPECT_EQ(line.counters().bytes_forwarded, 1500u);
}

TEST(DelayLine, WithoutJitterFramesLeaveInArrivalOrder) {
  DelayLine line(delayed(milliseconds(100)));
  const auto t0 = DelayLine::Clock::time_point{};
  // Bursts: several frames at the same instant, then a gap.
  for (std::uint32_t i = 0; i < 300; ++i) line.push(frame_of(i), t0 + milliseconds(i / 3));
  std::vector<std::uint32_t> order;
  DelayLine::Frame out;
  for (int ms = 0; ms <= 300; ++ms) {
    const auto now = t0 + milliseconds(ms);
    while (line.pop_due(now, out)) {
      order.push_back(id_of(out));
      // Never before its arrival + delay.
      EXPECT_GE(now, t0 + milliseconds(id_of(out) / 3) + milliseconds(100));
    }
  }
  ASSERT_EQ(order.size(), 300u);
  for (std::uint32_t i = 0; i < 300; ++i) EXPECT_EQ(order[i], i);
  EXPECT_EQ(line.counters().reordered, 0u);
  EXPECT_EQ(line.counters().max_queued, 300u);  // the first leaves at 100 ms, the last came at 99
}

TEST(DelayLine, JitterStaysWithinItsBoundsAndReordersCloseFrames) {
  LinkProfile p = delayed(milliseconds(100));
  p.jitter = milliseconds(20);
  p.seed = 42;
  DelayLine line(p);
  const auto t0 = DelayLine::Clock::time_point{};
  const int n = 2000;
  for (int i = 0; i < n; ++i) line.push(frame_of(i), t0 + milliseconds(i));
  std::vector<std::uint32_t> order;
  DelayLine::Frame out;
  for (int ms = 0; ms <= n + 200; ++ms) {
    const auto now = t0 + milliseconds(ms);
    while (line.pop_due(now, out)) {
      const auto arrival = t0 + milliseconds(id_of(out));
      // The step is 1 ms: released within the millisecond after its release time.
      EXPECT_GE(now, arrival + milliseconds(80));
      EXPECT_LE(now, arrival + milliseconds(121));
      order.push_back(id_of(out));
    }
  }
  ASSERT_EQ(order.size(), static_cast<std::size_t>(n));
  int inversions = 0;
  for (std::size_t i = 1; i < order.size(); ++i) inversions += order[i] < order[i - 1];
  // Frames 1 ms apart with +-20 ms of jitter: most neighbours swap at least once.
  EXPECT_GT(inversions, n / 4);
  // The counter: frames that left after one that arrived later than they did.
  std::uint32_t highest = 0;
  std::uint64_t late = 0;
  for (std::size_t i = 0; i < order.size(); ++i) {
    if (i > 0 && order[i] < highest) ++late;
    highest = std::max(highest, order[i]);
  }
  EXPECT_EQ(line.counters().reordered, late);
  EXPECT_GT(late, 0u);
}

TEST(DelayLine, LossDropsAboutTheFractionAndCountsEveryFrame) {
  LinkProfile p = delayed(milliseconds(1));
  p.loss_fraction = 0.1;
  p.queue_limit_frames = 100000;
  DelayLine line(p);
  const int n = 20000;
  int lost = 0;
  for (int i = 0; i < n; ++i)
    lost += line.push(frame_of(i), DelayLine::Clock::time_point{}) == DelayLine::Admission::lost;
  const auto& c = line.counters();
  EXPECT_EQ(c.received, static_cast<std::uint64_t>(n));
  EXPECT_EQ(c.lost, static_cast<std::uint64_t>(lost));
  // Binomial(20000, 0.1): sd 42 frames; 5 sd either side.
  EXPECT_NEAR(lost, n / 10, 210);
  EXPECT_EQ(line.queued(), static_cast<std::size_t>(n - lost));
}

TEST(DelayLine, FullLossForwardsNothing) {
  LinkProfile p;
  p.loss_fraction = 1.0;
  DelayLine line(p);
  for (int i = 0; i < 100; ++i) line.push(frame_of(i), DelayLine::Clock::time_point{});
  DelayLine::Frame out;
  EXPECT_FALSE(line.pop_due(DelayLine::Clock::time_point{} + std::chrono::hours(1), out));
  EXPECT_EQ(line.counters().lost, 100u);
}

TEST(DelayLine, FramesBeyondTheQueueLimitAreDroppedAndCounted) {
  LinkProfile p = delayed(milliseconds(100));
  p.queue_limit_frames = 10;
  DelayLine line(p);
  const auto t0 = DelayLine::Clock::time_point{};
  for (int i = 0; i < 15; ++i) {
    EXPECT_EQ(line.push(frame_of(i), t0),
              i < 10 ? DelayLine::Admission::queued : DelayLine::Admission::dropped_queue_full);
  }
  EXPECT_EQ(line.counters().dropped_queue_full, 5u);
  EXPECT_EQ(line.queued(), 10u);
  DelayLine::Frame out;
  ASSERT_TRUE(line.pop_due(t0 + milliseconds(100), out));
  EXPECT_EQ(id_of(out), 0u);
  // Room again for one.
  EXPECT_EQ(line.push(frame_of(99), t0 + milliseconds(100)), DelayLine::Admission::queued);
  int forwarded = 1;
  while (line.pop_due(t0 + milliseconds(300), out)) ++forwarded;
  EXPECT_EQ(forwarded, 11);
  EXPECT_EQ(line.counters().forwarded + line.counters().dropped_queue_full,
            line.counters().received);
}

}  // namespace

// Per-stream statistics: counters, latency quantiles, frames/s and the sliding window.

#include "litamin2/daemon/stream_stats.hpp"

#include <gtest/gtest.h>

#include <thread>

using namespace litamin2::daemon;
using namespace std::chrono_literals;
using Clock = StreamStats::Clock;

TEST(Quantile, NearestRank) {
  std::vector<double> v;
  EXPECT_EQ(quantile(v, 0.5), 0.0);
  for (int i = 100; i >= 1; --i) v.push_back(i);
  EXPECT_EQ(quantile(v, 0.5), 50.0);
  EXPECT_EQ(quantile(v, 0.99), 99.0);
  EXPECT_EQ(quantile(v, 1.0), 100.0);
  EXPECT_EQ(quantile(v, 0.0), 1.0);
  std::vector<double> one{7.0};
  EXPECT_EQ(quantile(one, 0.99), 7.0);
}

TEST(StreamStats, CountsAndLatency) {
  StreamStats stats(10s);
  const Clock::time_point t0 = Clock::now();
  for (int i = 0; i < 100; ++i) {
    stats.record_received();
    // Frame i arrives at t0 + 100 ms * i, is published (i + 1) ms later.
    const auto arrival = t0 + i * 100ms;
    stats.record_result(arrival, arrival + (i + 1) * 1ms, i % 10 == 0, i != 0, 1000 + i);
  }
  stats.record_dropped(3);
  stats.record_bad_message("bad_row_step");
  stats.record_bad_message("malformed_cdr");
  stats.record_failed();
  const StatsSnapshot s = stats.snapshot(t0 + 99 * 100ms + 100ms);
  EXPECT_EQ(s.frames_received, 100u);
  EXPECT_EQ(s.frames_processed, 100u);
  EXPECT_EQ(s.frames_dropped, 3u);
  EXPECT_EQ(s.bad_messages, 2u);
  EXPECT_EQ(s.bad_message_reasons.at("bad_row_step"), 1u);
  EXPECT_EQ(s.bad_message_reasons.at("malformed_cdr"), 1u);
  EXPECT_EQ(s.frames_failed, 1u);
  EXPECT_EQ(s.frames_unregistered, 1u);
  EXPECT_EQ(s.keyframes, 10u);
  EXPECT_EQ(s.map_size, 1099u);
  EXPECT_EQ(s.window_samples, 100u);
  EXPECT_NEAR(s.latency_p50_ms, 50.0, 1e-9);
  EXPECT_NEAR(s.latency_p99_ms, 99.0, 1e-9);
  EXPECT_NEAR(s.latency_max_ms, 100.0, 1e-9);
  // 100 results over 9.9 s + 99 ms of growing latency.
  EXPECT_NEAR(s.frames_per_second, 99.0 / (9.9 + 0.099), 1e-6);
}

TEST(StreamStats, TrackingCpuAddsUpOverFrames) {
  StreamStats stats;
  EXPECT_EQ(stats.snapshot().tracking_cpu_s, 0.0);
  stats.record_tracking_cpu(0.004);
  stats.record_tracking_cpu(0.0025);
  EXPECT_NEAR(stats.snapshot().tracking_cpu_s, 0.0065, 1e-12);
}

TEST(StreamStats, WindowForgetsOldResults) {
  StreamStats stats(1s);
  const Clock::time_point t0 = Clock::now();
  for (int i = 0; i < 10; ++i) stats.record_result(t0, t0 + 500ms, false, true, 1);  // old, slow
  for (int i = 0; i < 10; ++i) {
    const auto arrival = t0 + 5s + i * 100ms;
    stats.record_result(arrival, arrival + 2ms, false, true, 1);
  }
  const StatsSnapshot s = stats.snapshot(t0 + 6s);
  EXPECT_EQ(s.window_samples, 10u);
  EXPECT_NEAR(s.latency_p99_ms, 2.0, 1e-9);
  EXPECT_NEAR(s.frames_per_second, 10.0, 1e-6);
  EXPECT_EQ(s.frames_processed, 20u);  // counters are totals
  const StatsSnapshot later = stats.snapshot(t0 + 60s);
  EXPECT_EQ(later.window_samples, 0u);
  EXPECT_EQ(later.frames_per_second, 0.0);
  EXPECT_EQ(later.latency_p50_ms, 0.0);
}

TEST(StreamStats, LatencyHistogramKeepsEveryFrameBeyondTheWindow) {
  StreamStats stats(1s, 4);
  const Clock::time_point t0 = Clock::now();
  // 10 frames of 500 ms and 10 of 2 ms; the window (1 s, at most 4 samples) forgets most of
  // them, the Prometheus histogram none.
  for (int i = 0; i < 10; ++i) stats.record_result(t0, t0 + 500ms, false, true, 1);
  for (int i = 0; i < 10; ++i) stats.record_result(t0 + 5s, t0 + 5s + 2ms, false, true, 1);
  const StatsSnapshot s = stats.snapshot(t0 + 60s);
  EXPECT_EQ(s.window_samples, 0u);
  const litamin2::service::Histogram& h = s.latency_seconds;
  EXPECT_EQ(h.count(), 20u);
  EXPECT_NEAR(h.sum(), 10 * 0.5 + 10 * 0.002, 1e-9);
  const std::vector<std::uint64_t> c = h.cumulative_counts();
  for (std::size_t i = 0; i < c.size(); ++i) {
    const double le = h.upper_bounds()[i];
    const std::uint64_t expected = (le >= 0.002 ? 10u : 0u) + (le >= 0.5 ? 10u : 0u);
    EXPECT_EQ(c[i], expected) << "le " << le;
  }
}

TEST(StreamStats, SampleCountIsBounded) {
  StreamStats stats(10s, 16);
  const Clock::time_point t0 = Clock::now();
  for (int i = 0; i < 1000; ++i) stats.record_result(t0, t0 + 1ms, false, true, 1);
  EXPECT_EQ(stats.snapshot(t0 + 2ms).window_samples, 16u);
}

TEST(StreamStats, ConcurrentUpdatesAndSnapshots) {
  StreamStats stats;
  std::thread writer([&] {
    for (int i = 0; i < 20000; ++i) {
      stats.record_received();
      const auto now = Clock::now();
      stats.record_result(now, now, false, true, i);
    }
  });
  std::thread reader([&] {
    for (int i = 0; i < 200; ++i) {
      const StatsSnapshot s = stats.snapshot();
      EXPECT_LE(s.frames_processed, s.frames_received);
    }
  });
  writer.join();
  reader.join();
  EXPECT_EQ(stats.snapshot().frames_processed, 20000u);
}

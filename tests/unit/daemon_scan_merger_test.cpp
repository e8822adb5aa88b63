// Merging the scans of several sensors of one vehicle: extrinsics applied (not inverted),
// per-point times re-expressed relative to the merged stamp, listed order, window and timeout,
// a sensor that stops counted as missing, old scans rejected and counted.

#include "litamin2/daemon/scan_merger.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

using namespace litamin2;
using namespace litamin2::daemon;

namespace {

using Clock = std::chrono::steady_clock;

const Clock::time_point kT0 = Clock::time_point(std::chrono::seconds(1000));

Stamp at(double seconds) {
  return Stamp::from_seconds(seconds);
}

Frame scan(double stamp_s, std::vector<Eigen::Vector3f> points, std::vector<float> times = {},
           Clock::time_point arrival = kT0) {
  Frame f;
  f.stamp = at(stamp_s);
  f.cloud.points = std::move(points);
  f.cloud.times = std::move(times);
  f.arrival = arrival;
  return f;
}

/// Sensor 1 is 1 m forward, 2 m left of the base and turned 90 degrees left.
Eigen::Isometry3d turned_left() {
  Eigen::Isometry3d e = Eigen::Isometry3d::Identity();
  e.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  e.translation() = Eigen::Vector3d(1.0, 2.0, 0.0);
  return e;
}

ScanMerger two_sensors(ScanMergerConfig config = {}) {
  return ScanMerger({Eigen::Isometry3d::Identity(), turned_left()}, config);
}

}  // namespace

TEST(ScanMerger, AppliesTheExtrinsicSensorToBaseNotItsInverse) {
  ScanMerger merger = two_sensors();
  EXPECT_TRUE(merger.add(0, scan(10.0, {{5, 0, 0}})).empty());
  // 1 m ahead of sensor 1 is 1 m to the base's left of the sensor: (1, 3, 0) in the base.
  const std::vector<Frame> out = merger.add(1, scan(10.01, {{1, 0, 0}}));
  ASSERT_EQ(out.size(), 1u);
  const PointCloud& cloud = out[0].cloud;
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_EQ(cloud.points[0], Eigen::Vector3f(5, 0, 0));  // identity: untouched
  EXPECT_NEAR(cloud.points[1].x(), 1.0f, 1e-6);
  EXPECT_NEAR(cloud.points[1].y(), 3.0f, 1e-6);
  EXPECT_NEAR(cloud.points[1].z(), 0.0f, 1e-6);
  // The inverse would have put it at (-2, 0, 0) in the base.
  EXPECT_GT((cloud.points[1] - Eigen::Vector3f(-2, 0, 0)).norm(), 1.0f);
}

TEST(ScanMerger, ReexpressesPointTimesRelativeToTheEarliestStamp) {
  ScanMerger merger = two_sensors();
  // Sensor 1's scan is stamped 20 ms after sensor 0's: its points' times move 20 ms later.
  EXPECT_TRUE(merger.add(1, scan(10.02, {{1, 0, 0}, {2, 0, 0}}, {-0.05f, 0.01f})).empty());
  const std::vector<Frame> out = merger.add(0, scan(10.0, {{3, 0, 0}}, {0.04f}));
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].stamp, at(10.0));
  const std::vector<float>& times = out[0].cloud.times;
  ASSERT_EQ(times.size(), 3u);
  EXPECT_NEAR(times[0], 0.04f, 1e-6);           // sensor 0 first (listed order)
  EXPECT_NEAR(times[1], -0.05f + 0.02f, 1e-6);  // -0.03, not -0.07
  EXPECT_NEAR(times[2], 0.01f + 0.02f, 1e-6);
}

TEST(ScanMerger, ScanWithoutTimesTakesItsStampOffsetWhenAnotherHasTimes) {
  ScanMerger merger = two_sensors();
  merger.add(0, scan(10.0, {{3, 0, 0}}, {0.04f}));
  const std::vector<Frame> out = merger.add(1, scan(10.03, {{1, 0, 0}, {2, 0, 0}}));
  ASSERT_EQ(out.size(), 1u);
  ASSERT_EQ(out[0].cloud.times.size(), 3u);
  EXPECT_NEAR(out[0].cloud.times[1], 0.03f, 1e-6);
  EXPECT_NEAR(out[0].cloud.times[2], 0.03f, 1e-6);
  // Neither has times: the merged frame has none.
  ScanMerger plain = two_sensors();
  plain.add(0, scan(10.0, {{3, 0, 0}}));
  const std::vector<Frame> untimed = plain.add(1, scan(10.03, {{1, 0, 0}}));
  ASSERT_EQ(untimed.size(), 1u);
  EXPECT_FALSE(untimed[0].cloud.has_times());
}

TEST(ScanMerger, KeepsIntensitiesOnlyWhenEveryScanHasThem) {
  ScanMerger merger = two_sensors();
  Frame a = scan(10.0, {{3, 0, 0}});
  a.cloud.intensities = {7.0f};
  Frame b = scan(10.01, {{1, 0, 0}});
  b.cloud.intensities = {9.0f};
  merger.add(0, a);
  const std::vector<Frame> both = merger.add(1, b);
  ASSERT_EQ(both.size(), 1u);
  EXPECT_EQ(both[0].cloud.intensities, (std::vector<float>{7.0f, 9.0f}));
  Frame c = scan(10.1, {{3, 0, 0}});
  c.cloud.intensities = {7.0f};
  merger.add(0, c);
  const std::vector<Frame> one = merger.add(1, scan(10.11, {{1, 0, 0}}));
  ASSERT_EQ(one.size(), 1u);
  EXPECT_FALSE(one[0].cloud.has_intensities());
}

TEST(ScanMerger, PointsComeInListedOrderWhateverTheArrivalOrder) {
  ScanMerger ab = two_sensors();
  ScanMerger ba = two_sensors();
  ab.add(0, scan(10.0, {{5, 0, 0}}, {0.0f}));
  const std::vector<Frame> first = ab.add(1, scan(10.01, {{1, 0, 0}}, {0.0f}));
  ba.add(1, scan(10.01, {{1, 0, 0}}, {0.0f}));
  const std::vector<Frame> second = ba.add(0, scan(10.0, {{5, 0, 0}}, {0.0f}));
  ASSERT_EQ(first.size(), 1u);
  ASSERT_EQ(second.size(), 1u);
  EXPECT_EQ(first[0].stamp, second[0].stamp);
  EXPECT_EQ(first[0].cloud.points, second[0].cloud.points);
  EXPECT_EQ(first[0].cloud.times, second[0].cloud.times);
  EXPECT_EQ(second[0].cloud.points[0], Eigen::Vector3f(5, 0, 0));
}

TEST(ScanMerger, ThreeSensorsWaitForTheLast) {
  ScanMerger merger({Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity(), turned_left()},
                    {});
  EXPECT_TRUE(merger.add(2, scan(10.02, {{1, 0, 0}})).empty());
  EXPECT_TRUE(merger.add(0, scan(10.0, {{2, 0, 0}})).empty());
  EXPECT_TRUE(merger.pending());
  const std::vector<Frame> out = merger.add(1, scan(10.01, {{3, 0, 0}}));
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].cloud.size(), 3u);
  EXPECT_EQ(merger.counters().frames, 1u);
  EXPECT_EQ(merger.counters().incomplete_frames, 0u);
  EXPECT_FALSE(merger.pending());
}

TEST(ScanMerger, TimeoutEmitsWhatArrivedAndCountsTheMissingSensor) {
  ScanMergerConfig config;
  config.timeout_s = 0.2;
  ScanMerger merger = two_sensors(config);
  merger.add(0, scan(10.0, {{5, 0, 0}}, {}, kT0));
  EXPECT_TRUE(merger.expire(kT0 + std::chrono::milliseconds(199)).empty());
  const std::vector<Frame> out = merger.expire(kT0 + std::chrono::milliseconds(200));
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].cloud.size(), 1u);
  EXPECT_EQ(out[0].arrival, kT0);
  EXPECT_EQ(merger.counters().frames, 1u);
  EXPECT_EQ(merger.counters().incomplete_frames, 1u);
  EXPECT_EQ(merger.counters().sensors[0].missing, 0u);
  EXPECT_EQ(merger.counters().sensors[1].missing, 1u);
  EXPECT_TRUE(merger.expire(kT0 + std::chrono::seconds(5)).empty());  // nothing pending
  // The late scan of the emitted frame is rejected, not merged into the next.
  EXPECT_TRUE(merger.add(1, scan(10.01, {{1, 0, 0}})).empty());
  EXPECT_EQ(merger.counters().sensors[1].late, 1u);
  EXPECT_EQ(merger.counters().rejected(), 1u);
}

TEST(ScanMerger, AScanBeyondTheWindowClosesThePendingFrame) {
  ScanMergerConfig config;
  config.window_s = 0.05;
  ScanMerger merger = two_sensors(config);
  merger.add(0, scan(10.0, {{5, 0, 0}}));
  const std::vector<Frame> out = merger.add(1, scan(10.06, {{1, 0, 0}}));
  ASSERT_EQ(out.size(), 1u);  // sensor 0 alone; sensor 1's scan opens the next frame
  EXPECT_EQ(out[0].stamp, at(10.0));
  EXPECT_EQ(out[0].cloud.size(), 1u);
  EXPECT_TRUE(merger.pending());
  EXPECT_EQ(merger.counters().sensors[1].missing, 1u);
  // Just within the window: merged.
  const std::vector<Frame> next = merger.add(0, scan(10.11, {{5, 0, 0}}));
  ASSERT_EQ(next.size(), 1u);
  EXPECT_EQ(next[0].stamp, at(10.06));
  EXPECT_EQ(next[0].cloud.size(), 2u);
}

TEST(ScanMerger, ASecondScanOfTheSameSensorClosesThePendingFrame) {
  ScanMergerConfig config;
  config.window_s = 0.2;
  ScanMerger merger = two_sensors(config);
  merger.add(0, scan(10.0, {{5, 0, 0}}));
  const std::vector<Frame> out = merger.add(0, scan(10.1, {{6, 0, 0}}));
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].cloud.points[0], Eigen::Vector3f(5, 0, 0));
  EXPECT_EQ(merger.counters().sensors[1].missing, 1u);
  EXPECT_TRUE(merger.pending());
  // Sensor 1's scan of the emitted frame (before the scan that closed it) is late; one at the
  // next frame's stamp joins it.
  EXPECT_TRUE(merger.add(1, scan(10.05, {{1, 0, 0}})).empty());
  EXPECT_EQ(merger.counters().sensors[1].late, 1u);
  const std::vector<Frame> next = merger.add(1, scan(10.1, {{1, 0, 0}}));
  ASSERT_EQ(next.size(), 1u);
  EXPECT_EQ(next[0].cloud.size(), 2u);
}

TEST(ScanMerger, ASensorThatStopsIsCountedMissingInEveryFrame) {
  ScanMerger merger = two_sensors();
  std::vector<Frame> frames;
  auto take = [&](std::vector<Frame> out) {
    for (Frame& f : out) frames.push_back(std::move(f));
  };
  for (int i = 0; i < 3; ++i) {
    take(merger.add(0, scan(10.0 + 0.1 * i, {{5, 0, 0}})));
    take(merger.add(1, scan(10.005 + 0.1 * i, {{1, 0, 0}})));
  }
  ASSERT_EQ(frames.size(), 3u);
  for (int i = 3; i < 8; ++i) take(merger.add(0, scan(10.0 + 0.1 * i, {{5, 0, 0}})));
  take(merger.flush());
  ASSERT_EQ(frames.size(), 8u);  // none dropped
  const ScanMergerCounters& c = merger.counters();
  EXPECT_EQ(c.frames, 8u);
  EXPECT_EQ(c.incomplete_frames, 5u);
  EXPECT_EQ(c.sensors[0].missing, 0u);
  EXPECT_EQ(c.sensors[1].missing, 5u);
  EXPECT_EQ(c.missing(), 5u);
  EXPECT_EQ(c.sensors[0].scans, 8u);
  EXPECT_EQ(c.sensors[1].scans, 3u);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    EXPECT_EQ(frames[i].sequence, i);
    EXPECT_EQ(frames[i].cloud.size(), i < 3 ? 2u : 1u);
    if (i > 0) {
      EXPECT_LT(frames[i - 1].stamp, frames[i].stamp);
    }
  }
}

TEST(ScanMerger, RejectsOutOfOrderAndLateScans) {
  ScanMerger merger = two_sensors();
  merger.add(0, scan(10.0, {{5, 0, 0}}));
  // Sensor 0 again, older: out of order (per sensor), not merged, the frame still pending.
  EXPECT_TRUE(merger.add(0, scan(9.99, {{5, 0, 0}})).empty());
  EXPECT_EQ(merger.counters().sensors[0].out_of_order, 1u);
  // Sensor 0 at the same stamp: out of order too.
  EXPECT_TRUE(merger.add(0, scan(10.0, {{5, 0, 0}})).empty());
  EXPECT_EQ(merger.counters().sensors[0].out_of_order, 2u);
  EXPECT_EQ(merger.add(1, scan(10.01, {{1, 0, 0}})).size(), 1u);
  // Sensor 0 after its last scan but within the frame emitted: late.
  EXPECT_TRUE(merger.add(0, scan(10.005, {{5, 0, 0}})).empty());
  EXPECT_EQ(merger.counters().sensors[0].late, 1u);
  // A frame pending at 11.0: sensor 1 stamped more than the window before it is late.
  merger.add(0, scan(11.0, {{5, 0, 0}}));
  EXPECT_TRUE(merger.add(1, scan(10.9, {{1, 0, 0}})).empty());
  EXPECT_EQ(merger.counters().sensors[1].late, 1u);
  EXPECT_EQ(merger.counters().rejected(), 4u);
  EXPECT_EQ(merger.counters().frames, 1u);
  EXPECT_TRUE(merger.pending());
}

TEST(ScanMerger, RestartForgetsStampsAfterEmittingThePendingFrame) {
  ScanMerger merger = two_sensors();
  merger.add(0, scan(10.0, {{5, 0, 0}}));
  merger.add(1, scan(10.0, {{1, 0, 0}}));
  merger.add(0, scan(10.1, {{5, 0, 0}}));
  const std::vector<Frame> out = merger.restart();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(merger.counters().sensors[1].missing, 1u);
  // The publisher starts its stamps over: accepted.
  merger.add(0, scan(1.0, {{5, 0, 0}}));
  EXPECT_EQ(merger.add(1, scan(1.0, {{1, 0, 0}})).size(), 1u);
  EXPECT_EQ(merger.counters().rejected(), 0u);
}

TEST(ScanMerger, RejectsBadConstruction) {
  EXPECT_THROW(ScanMerger({}, {}), std::invalid_argument);
  Eigen::Isometry3d scaled = Eigen::Isometry3d::Identity();
  scaled.linear() *= 2.0;
  EXPECT_THROW(ScanMerger({Eigen::Isometry3d::Identity(), scaled}, {}), std::invalid_argument);
  Eigen::Isometry3d mirrored = Eigen::Isometry3d::Identity();
  mirrored.linear()(2, 2) = -1.0;
  EXPECT_THROW(ScanMerger({mirrored}, {}), std::invalid_argument);
  Eigen::Isometry3d nan = Eigen::Isometry3d::Identity();
  nan.translation().x() = std::nan("");
  EXPECT_THROW(ScanMerger({nan}, {}), std::invalid_argument);
  ScanMergerConfig no_window;
  no_window.window_s = 0.0;
  EXPECT_THROW(ScanMerger({Eigen::Isometry3d::Identity()}, no_window), std::invalid_argument);
  ScanMergerConfig wide;
  wide.window_s = 0.6;
  EXPECT_TRUE(scan_merger_config_error(wide).has_value());
  ScanMergerConfig no_timeout;
  no_timeout.timeout_s = -1.0;
  EXPECT_TRUE(scan_merger_config_error(no_timeout).has_value());
  EXPECT_FALSE(scan_merger_config_error(ScanMergerConfig{}).has_value());
  ScanMerger merger = two_sensors();
  EXPECT_THROW(merger.add(2, scan(10.0, {{1, 0, 0}})), std::out_of_range);
}

TEST(ScanMerger, OneSensorPassesEachScanThroughAtOnce) {
  ScanMerger merger({turned_left()}, {});
  const std::vector<Frame> out = merger.add(0, scan(10.0, {{1, 0, 0}}, {0.01f}));
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].stamp, at(10.0));
  EXPECT_NEAR(out[0].cloud.points[0].y(), 3.0f, 1e-6);
  EXPECT_EQ(out[0].cloud.times, std::vector<float>{0.01f});
  EXPECT_EQ(merger.counters().incomplete_frames, 0u);
}

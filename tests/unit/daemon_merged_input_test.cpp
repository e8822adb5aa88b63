// A stream's merged input: scans of two sensors handed in from two threads reach the stream's
// processor as merged frames, in stamp order; expire() and flush() queue a frame a sensor
// left incomplete.

#include "litamin2/daemon/merged_input.hpp"

#include <gtest/gtest.h>

#include <mutex>
#include <thread>
#include <vector>

using namespace litamin2;
using namespace litamin2::daemon;
using namespace std::chrono_literals;

namespace {

Frame scan(std::int64_t stamp_ms, float x, std::chrono::steady_clock::time_point arrival) {
  Frame f;
  f.stamp = Stamp{stamp_ms * 1'000'000};
  f.cloud.points = {Eigen::Vector3f(x, 0, 0)};
  f.arrival = arrival;
  return f;
}

struct Recorder {
  std::mutex mutex;
  std::vector<Frame> frames;
};

Eigen::Isometry3d shifted(double x) {
  Eigen::Isometry3d e = Eigen::Isometry3d::Identity();
  e.translation().x() = x;
  return e;
}

}  // namespace

TEST(MergedInput, ScansOfTwoThreadsBecomeMergedFramesInStampOrder) {
  constexpr int kFrames = 200;
  StreamScheduler scheduler(2, kFrames);
  Recorder recorder;
  const auto handle = scheduler.add_stream("car1", [&](Frame& f) {
    std::lock_guard lock(recorder.mutex);
    recorder.frames.push_back(std::move(f));
  });
  ScanMergerConfig config;
  config.window_s = 0.05;
  MergedInput input({shifted(0.0), shifted(10.0)}, config, scheduler, handle);
  const auto now = std::chrono::steady_clock::now();
  auto feed = [&](std::size_t sensor, std::int64_t offset_ms) {
    for (int i = 0; i < kFrames; ++i) input.add(sensor, scan(1000 + 100 * i + offset_ms, 1, now));
  };
  std::thread a(feed, 0, 0);
  std::thread b(feed, 1, 5);
  a.join();
  b.join();
  input.flush();
  EXPECT_TRUE(scheduler.drain(10s).complete);
  const ScanMergerCounters counters = input.counters();
  // Two threads race: a sensor may run ahead of the other by more than a window, which closes
  // frames early; every scan is either merged or rejected and counted, none lost.
  EXPECT_EQ(counters.sensors[0].scans + counters.sensors[0].late, std::uint64_t{kFrames});
  EXPECT_EQ(counters.sensors[1].scans + counters.sensors[1].late, std::uint64_t{kFrames});
  ASSERT_EQ(recorder.frames.size(), counters.frames);
  std::size_t points = 0;
  for (std::size_t i = 0; i < recorder.frames.size(); ++i) {
    const Frame& f = recorder.frames[i];
    points += f.cloud.size();
    if (i > 0) {
      EXPECT_LT(recorder.frames[i - 1].stamp, f.stamp);
    }
    // Sensor 1's point is moved by its extrinsic.
    for (const Eigen::Vector3f& p : f.cloud.points) EXPECT_TRUE(p.x() == 1.0f || p.x() == 11.0f);
  }
  EXPECT_EQ(points, counters.sensors[0].scans + counters.sensors[1].scans);
}

TEST(MergedInput, ExpireQueuesTheIncompleteFrameAfterTheTimeout) {
  StreamScheduler scheduler(1, 8);
  Recorder recorder;
  const auto handle = scheduler.add_stream("car1", [&](Frame& f) {
    std::lock_guard lock(recorder.mutex);
    recorder.frames.push_back(std::move(f));
  });
  ScanMergerConfig config;
  config.timeout_s = 0.1;
  MergedInput input({shifted(0.0), shifted(10.0)}, config, scheduler, handle);
  const auto t0 = std::chrono::steady_clock::now();
  input.add(0, scan(1000, 1, t0));
  input.expire(t0 + 50ms);
  input.expire(t0 + 100ms);
  EXPECT_TRUE(scheduler.drain(10s).complete);
  ASSERT_EQ(recorder.frames.size(), 1u);
  EXPECT_EQ(recorder.frames[0].cloud.size(), 1u);
  EXPECT_EQ(input.counters().sensors[1].missing, 1u);
}

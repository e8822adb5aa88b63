// DaemonNode over real DDS, loopback-only profile (UDP on 127.0.0.1 with unicast discovery,
// shared memory; no multicast): malformed PointCloud2 messages are counted and dropped without
// disturbing their stream or another one; a stream published faster than it is processed drops
// its oldest frames and counts them, and its memory stays flat while it does.

#include "litamin2/daemon/daemon_config.hpp"

#include <gtest/gtest.h>

#include "litamin2/daemon/dds/daemon_node.hpp"
#include "litamin2/dds/pointcloud2_conversion.hpp"
#include "support/daemon_dds.hpp"
#include "support/synthetic_scene.hpp"

#include <cmath>

namespace fdds = eprosima::fastdds::dds;
using namespace litamin2;
using namespace litamin2::daemon;
using namespace litamin2::testing;
using namespace std::chrono_literals;

namespace {

sensor_msgs::msg::PointCloud2 scan_message(int i) {
  static const PointCloud scene = litamin2::testing::synthetic_scene(3, 20000);
  Eigen::Isometry3d sensor = Eigen::Isometry3d::Identity();
  sensor.translation().x() = 0.5 * i;
  return litamin2::dds::to_pointcloud2(litamin2::testing::transformed(scene, sensor.inverse()),
                                       Stamp::from_seconds(100.0 + 0.1 * i), "lidar");
}

}  // namespace

TEST(DaemonNode, BadMessagesAreCountedAndDropped) {
  const int domain = test_domain();
  DaemonNode node(config_of("dds: {domain: " + std::to_string(domain) + R"(, profile: loopback}
streams: [{id: dnode_good}, {id: dnode_bad}]
threads: 2
queue_depth: 100
)"));
  CloudPublisher publisher(domain);
  ASSERT_TRUE(publisher.ok());
  fdds::DataWriter* good = publisher.writer("rt/dnode_good/points");
  fdds::DataWriter* bad = publisher.writer("rt/dnode_bad/points");
  ASSERT_TRUE(good && bad);
  ASSERT_TRUE(poll_until(node, [&](const auto& st) {
    return find(st, "dnode_good").reading && find(st, "dnode_bad").reading && matched(good) &&
           matched(bad);
  })) << "readers were not created / matched";

  std::vector<sensor_msgs::msg::PointCloud2> malformed;
  auto variant = [&](auto change) {
    sensor_msgs::msg::PointCloud2 msg = scan_message(0);
    change(msg);
    malformed.push_back(std::move(msg));
  };
  variant([](auto& m) { m.data().resize(m.data().size() - 5); });      // truncated
  variant([](auto& m) { m.point_step(8); });                           // z and intensity outside
  variant([](auto& m) { m.row_step(m.row_step() / 2); });              // row_step too small
  variant([](auto& m) { m.fields().erase(m.fields().begin() + 2); });  // no z
  variant([](auto& m) { m.fields()[0].datatype(5); });                 // x as INT32
  variant([](auto& m) { m.width(m.width() + 1); });                    // width vs data size
  variant([](auto& m) { m.fields()[1].offset(m.point_step()); });      // y past the point
  for (auto& msg : malformed) ASSERT_TRUE(bad->write(&msg));
  // The bad stream's tracker is untouched: its next good frames are processed normally.
  for (int i = 0; i < 2; ++i) {
    auto msg = scan_message(i);
    ASSERT_TRUE(bad->write(&msg));
  }
  constexpr int kGood = 8;
  for (int i = 0; i < kGood; ++i) {
    auto msg = scan_message(i);
    ASSERT_TRUE(good->write(&msg));
  }
  ASSERT_TRUE(poll_until(node,
                         [&](const auto& st) {
                           return find(st, "dnode_good").stats.frames_processed == kGood &&
                                  find(st, "dnode_bad").stats.frames_processed == 2 &&
                                  find(st, "dnode_bad").stats.bad_messages == malformed.size();
                         }))
      << "bad " << find(node.status(), "dnode_bad").stats.bad_messages << " processed "
      << find(node.status(), "dnode_bad").stats.frames_processed;
  const auto status = node.status();
  EXPECT_EQ(find(status, "dnode_good").stats.bad_messages, 0u);
  EXPECT_EQ(find(status, "dnode_good").counters.dropped, 0u);
  EXPECT_EQ(find(status, "dnode_bad").stats.frames_unregistered, 1u);  // only the first frame
  EXPECT_EQ(find(status, "dnode_good").stats.frames_unregistered, 1u);
  EXPECT_TRUE(node.shutdown().complete);
}

TEST(DaemonNode, OverloadDropsOldestFrames) {
  const int domain = test_domain();
  DaemonNode node(config_of("dds: {domain: " + std::to_string(domain) + R"(, profile: loopback}
streams: [{id: dnode_fast}]
threads: 1
queue_depth: 2
shutdown_timeout_s: 5
)"));
  CloudPublisher publisher(domain);
  fdds::DataWriter* writer = publisher.writer("rt/dnode_fast/points");
  ASSERT_TRUE(writer);
  ASSERT_TRUE(poll_until(
      node, [&](const auto& st) { return find(st, "dnode_fast").reading && matched(writer); }));
  constexpr int kFrames = 40;
  std::vector<sensor_msgs::msg::PointCloud2> messages;
  for (int i = 0; i < kFrames; ++i) messages.push_back(scan_message(i));
  for (auto& msg : messages) ASSERT_TRUE(writer->write(&msg));
  ASSERT_TRUE(poll_until(node, [&](const auto& st) {
    return find(st, "dnode_fast").stats.frames_received == kFrames;
  }));
  EXPECT_TRUE(node.shutdown().complete);
  const StreamStatus s = find(node.status(), "dnode_fast");
  EXPECT_GT(s.counters.dropped, 0u);
  EXPECT_EQ(s.stats.frames_processed + s.counters.dropped, static_cast<std::uint64_t>(kFrames));
  EXPECT_EQ(s.counters.submitted, static_cast<std::uint64_t>(kFrames));
}

TEST(DaemonNode, OverloadKeepsMemoryFlat) {
  // A stream published far faster than it is processed (reliable, so every frame arrives)
  // into a queue of depth 2 on one thread: most frames are dropped, and the process's memory
  // (the node runs in this process) after the first 100 frames and at the end differ by less
  // than kBoundMb. Unpaced, the writer sends 400 frames in ~0.2 s while ~4 are processed, so
  // it is paced at kRateHz (several times the processing rate here) for up to kMaxFrames /
  // kMaxPublishTime: processing, keyframes and map patches go on during the whole measurement.
  // In steady state everything is bounded: the queue (2 frames of 20k points, 2 x 240 KB), the
  // frame in processing, the writer's history (10 samples x 320 KB), the reader's (keep-last
  // 10), and the tracker's map (the sensor circles in a 4 m wide loop in one scene that every
  // scan sees whole, so the map is full after the first keyframes), and the map-patch writer
  // (transient-local, keep-all), which holds the latest outputs.map_patch_history patches per
  // stream for late readers: 100 here, ~32 KB each (every processed frame turns 9 degrees, so
  // is a keyframe), ~3 MB. 20 MB covers that plus allocator and DDS pool noise (measured on
  // 2026-12-01: +6 MB over 920 keyframes, +7 MB over 4620 in a 40 s run); leaking one
  // converted scan (240 KB) per frame received after the first 100 would add hundreds of MB,
  // and patches held without a limit (as before that date) added 30 MB over 850 keyframes.
  constexpr double kBoundMb = 20.0;
  constexpr int kMaxFrames = 4000;
  constexpr double kRateHz = 400.0;
  constexpr auto kMaxPublishTime = 15s;
  constexpr int kLoop = 40;  // frames per loop of the sensor's path
  const int domain = test_domain();
  DaemonNode node(config_of("dds: {domain: " + std::to_string(domain) + R"(, profile: loopback}
streams: [{id: dnode_flood}]
threads: 1
queue_depth: 2
outputs: {map_patch_history: 100}
shutdown_timeout_s: 5
)"));
  CloudPublisher publisher(domain);
  fdds::DataWriter* writer = publisher.writer("rt/dnode_flood/points", 10);
  ASSERT_TRUE(writer);
  ASSERT_TRUE(poll_until(
      node, [&](const auto& st) { return find(st, "dnode_flood").reading && matched(writer); }));
  // One loop of scans, re-stamped on every pass (stamps must increase).
  std::vector<sensor_msgs::msg::PointCloud2> loop;
  const PointCloud scene = litamin2::testing::synthetic_scene(5, 20000);
  for (int i = 0; i < kLoop; ++i) {
    const double a = 2.0 * M_PI * i / kLoop;
    Eigen::Isometry3d sensor = Eigen::Isometry3d::Identity();
    sensor.translation() << 2.0 * std::cos(a), 2.0 * std::sin(a), 0.0;
    sensor.linear() = Eigen::AngleAxisd(a + M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    loop.push_back(litamin2::dds::to_pointcloud2(transformed(scene, sensor.inverse()),
                                                 Stamp::from_seconds(0.0), "lidar"));
  }
  long rss_after_100_kb = -1;
  std::uint64_t published = 0;
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < kMaxFrames && std::chrono::steady_clock::now() - start < kMaxPublishTime;
       ++i) {
    std::this_thread::sleep_until(start + std::chrono::duration_cast<std::chrono::nanoseconds>(
                                              std::chrono::duration<double>(i / kRateHz)));
    auto& msg = loop[i % kLoop];
    msg.header().stamp().sec(1000 + i / 10);
    msg.header().stamp().nanosec(static_cast<std::uint32_t>(i % 10) * 100'000'000u);
    ASSERT_TRUE(writer->write(&msg));
    ++published;
    node.poll();
    if (published == 100) rss_after_100_kb = proc_status_kb("VmRSS");
  }
  const double publish_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_TRUE(poll_until(node,
                         [&](const auto& st) {
                           const StreamStatus& s = find(st, "dnode_flood");
                           return s.stats.frames_received == published &&
                                  s.stats.frames_processed + s.counters.dropped == published;
                         }))
      << "received " << find(node.status(), "dnode_flood").stats.frames_received << " of "
      << published;
  const long rss_end_kb = proc_status_kb("VmRSS");
  const StreamStatus s = find(node.status(), "dnode_flood");
  EXPECT_TRUE(node.shutdown().complete);
  const double diff_mb = (rss_end_kb - rss_after_100_kb) / 1024.0;
  std::printf(
      "%llu frames published in %.1f s: %llu processed, %llu dropped, %llu keyframes; "
      "RSS %.1f MB after 100 frames, %.1f MB at the end (peak %.1f MB)\n",
      static_cast<unsigned long long>(published), publish_s,
      static_cast<unsigned long long>(s.stats.frames_processed),
      static_cast<unsigned long long>(s.counters.dropped),
      static_cast<unsigned long long>(s.stats.keyframes), rss_after_100_kb / 1024.0,
      rss_end_kb / 1024.0, proc_status_kb("VmHWM") / 1024.0);
  ASSERT_GT(published, 100u);
  EXPECT_GT(s.counters.dropped, 0u);
  EXPECT_EQ(s.stats.frames_processed + s.counters.dropped, published);
  EXPECT_EQ(s.stats.bad_messages, 0u);
  EXPECT_EQ(s.stats.frames_out_of_order, 0u);
  EXPECT_LT(std::abs(diff_mb), kBoundMb);
}

// A stream taken over from another daemon: the origin is the last pose carried on at its twist,
// the new owner's outputs are the plain tracker's moved by it, keyframe ids continue.

#include "litamin2/daemon/stream_handover.hpp"
#include "litamin2/daemon/stream_processor.hpp"
#include "support/synthetic_scene.hpp"

#include <gtest/gtest.h>

#include <vector>

using namespace litamin2;
using namespace litamin2::daemon;

namespace {

class RecordingSink : public ResultSink {
 public:
  void publish_odometry(const OdometryOutput& o) override { poses.push_back(o.pose); }
  void publish_keyframe(const Keyframe& k) override {
    keyframe_ids.push_back(k.key.id);
    keyframe_poses.push_back(k.odom_pose);
  }
  std::vector<Eigen::Isometry3d> poses;
  std::vector<std::uint64_t> keyframe_ids;
  std::vector<Eigen::Isometry3d> keyframe_poses;
};

Stamp seconds(double s) {
  return Stamp{static_cast<std::int64_t>(s * 1e9)};
}

Eigen::Isometry3d some_pose() {
  Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
  p.linear() =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(0.1, 0.2, 1.0).normalized()).toRotationMatrix();
  p.translation() = Eigen::Vector3d(12.0, -3.0, 0.5);
  return p;
}

}  // namespace

TEST(HandoverOrigin, ConstantTwistCarriesThePoseOn) {
  HandoverSeed seed;
  seed.pose = some_pose();
  seed.stamp = seconds(100.0);
  seed.twist = Twist{Eigen::Vector3d(0, 0, 0.2), Eigen::Vector3d(8.0, 0, 0)};
  // Straight driving: 8 m/s for 1.5 s along the body's x axis, turning 0.3 rad.
  const Eigen::Isometry3d o = handover_origin(seed, seconds(101.5), 10.0);
  const Eigen::Isometry3d expected = seed.pose * motion_after(*seed.twist, 1.5);
  EXPECT_TRUE(o.isApprox(expected, 1e-12));
  const Eigen::Isometry3d relative = seed.pose.inverse() * o;
  EXPECT_NEAR(Eigen::AngleAxisd(relative.rotation()).angle(), 0.3, 1e-9);
  // Arc of radius 40 m over 0.3 rad: chord 2 r sin(0.15).
  EXPECT_NEAR(relative.translation().norm(), 80.0 * std::sin(0.15), 1e-9);
}

TEST(HandoverOrigin, NoTwistOrBadGapKeepsTheLastPose) {
  HandoverSeed seed;
  seed.pose = some_pose();
  seed.stamp = seconds(100.0);
  EXPECT_TRUE(handover_origin(seed, seconds(101.0), 10.0).isApprox(seed.pose, 0.0));
  seed.twist = Twist{Eigen::Vector3d::Zero(), Eigen::Vector3d(5.0, 0, 0)};
  EXPECT_TRUE(handover_origin(seed, seconds(99.0), 10.0).isApprox(seed.pose, 0.0));
  EXPECT_TRUE(handover_origin(seed, seconds(100.0), 10.0).isApprox(seed.pose, 0.0));
  EXPECT_TRUE(handover_origin(seed, seconds(111.0), 10.0).isApprox(seed.pose, 0.0));
  EXPECT_FALSE(handover_origin(seed, seconds(109.0), 10.0).isApprox(seed.pose, 1e-6));
}

TEST(StreamProcessor, TakenOverStreamContinuesTheOdometryFrameAndKeyframeIds) {
  const PointCloud scene = litamin2::testing::synthetic_scene(1, 30000);
  StreamConfig config;
  config.id = "car1";
  RecordingSink plain_sink, moved_sink;
  StreamStats plain_stats, moved_stats;
  StreamProcessor plain(config, plain_sink, plain_stats);
  HandoverSeed seed;
  seed.pose = some_pose();
  seed.stamp = seconds(99.9);
  seed.next_keyframe_id = 41;
  StreamProcessor moved(config, moved_sink, moved_stats, seed, 10.0);
  for (int i = 0; i < 5; ++i) {
    Eigen::Isometry3d sensor = Eigen::Isometry3d::Identity();
    sensor.translation() = Eigen::Vector3d(0.6 * i, 0.0, 0.0);
    Frame a;
    a.cloud = litamin2::testing::transformed(scene, sensor.inverse());
    a.sequence = static_cast<std::uint64_t>(i);
    a.stamp = seconds(100.0 + 0.1 * i);
    a.arrival = std::chrono::steady_clock::now();
    Frame b = a;
    plain.process(a);
    moved.process(b);
  }
  // No twist in the seed: the origin is the last pose.
  ASSERT_TRUE(moved.origin().has_value());
  EXPECT_TRUE(moved.origin()->isApprox(seed.pose, 0.0));
  ASSERT_EQ(plain_sink.poses.size(), 5u);
  ASSERT_EQ(moved_sink.poses.size(), 5u);
  for (std::size_t i = 0; i < 5; ++i)
    EXPECT_TRUE(moved_sink.poses[i].isApprox(seed.pose * plain_sink.poses[i], 1e-12)) << i;
  ASSERT_FALSE(moved_sink.keyframe_ids.empty());
  ASSERT_EQ(moved_sink.keyframe_ids.size(), plain_sink.keyframe_ids.size());
  for (std::size_t i = 0; i < moved_sink.keyframe_ids.size(); ++i) {
    EXPECT_EQ(moved_sink.keyframe_ids[i], 41 + plain_sink.keyframe_ids[i]);
    EXPECT_TRUE(
        moved_sink.keyframe_poses[i].isApprox(seed.pose * plain_sink.keyframe_poses[i], 1e-12));
  }
  EXPECT_EQ(moved.keyframes(), 41 + plain.keyframes());
}

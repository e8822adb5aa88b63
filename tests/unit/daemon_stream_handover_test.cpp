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

namespace {

Keyframe keyframe_at(std::uint64_t id, double stamp_s) {
  Keyframe k;
  k.key = KeyframeKey{"car1", id};
  k.stamp = seconds(stamp_s);
  return k;
}

std::vector<std::uint64_t> ids(const std::vector<Keyframe>& keyframes) {
  std::vector<std::uint64_t> out;
  for (const Keyframe& k : keyframes) out.push_back(k.key.id);
  return out;
}

/// Keeps every published keyframe whole (what the map patches carry) and the odometry.
class KeyframeSink : public ResultSink {
 public:
  void publish_odometry(const OdometryOutput& o) override { odometry.push_back(o); }
  void publish_keyframe(const Keyframe& k) override { keyframes.push_back(k); }
  std::vector<OdometryOutput> odometry;
  std::vector<Keyframe> keyframes;
};

}  // namespace

TEST(MapSeed, NewestWithinTheAgeOnePerIdOldestFirst) {
  std::vector<Keyframe> candidates = {keyframe_at(7, 99.0), keyframe_at(3, 90.0),
                                      keyframe_at(5, 97.0), keyframe_at(6, 98.0),
                                      keyframe_at(6, 98.0), keyframe_at(4, 95.5)};
  // At most 3, none older than 5 s before 100 s: 4 (95.5 s) qualifies by age, not by count.
  EXPECT_EQ(ids(select_map_seed(candidates, seconds(100.0), MapSeedLimits{3, 5.0})),
            (std::vector<std::uint64_t>{5, 6, 7}));
  EXPECT_EQ(ids(select_map_seed(candidates, seconds(100.0), MapSeedLimits{10, 5.0})),
            (std::vector<std::uint64_t>{4, 5, 6, 7}));
  EXPECT_EQ(ids(select_map_seed(candidates, seconds(100.0), MapSeedLimits{10, 100.0})),
            (std::vector<std::uint64_t>{3, 4, 5, 6, 7}));
  EXPECT_TRUE(select_map_seed(candidates, seconds(100.0), MapSeedLimits{0, 100.0}).empty());
  EXPECT_TRUE(select_map_seed(candidates, seconds(200.0), MapSeedLimits{10, 5.0}).empty());
}

TEST(MapSeed, TrackerSeedIsInTheFirstSensorFrame) {
  HandoverSeed seed;
  seed.pose = some_pose();
  seed.stamp = seconds(100.0);
  seed.twist = Twist{Eigen::Vector3d(0, 0, 0.2), Eigen::Vector3d(8.0, 0, 0)};
  seed.interval_s = 0.1;
  Keyframe k = keyframe_at(4, 99.9);
  k.odom_pose = some_pose();
  k.voxel_size = 1.5;
  k.distributions.resize(3);
  seed.map_keyframes = {k};
  Eigen::Isometry3d e = Eigen::Isometry3d::Identity();  // sensor in base
  e.linear() = Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitY()).toRotationMatrix();
  e.translation() = Eigen::Vector3d(1.2, 0.0, 1.8);
  const TrackerSeed t = tracker_seed(seed, seconds(100.5), 10.0, e);
  const Eigen::Isometry3d o = handover_origin(seed, seconds(100.5), 10.0);
  // The published base pose of the predicted sensor pose is O (base_pose: E T E^-1).
  EXPECT_TRUE(base_pose(t.predicted, e).isApprox(o, 1e-12));
  EXPECT_TRUE(base_pose(t.velocity, e).isApprox(motion_after(*seed.twist, 0.1), 1e-12));
  EXPECT_EQ(t.interval_s, 0.1);
  ASSERT_EQ(t.keyframes.size(), 1u);
  // make_keyframe's odom_pose is E T: the tracker pose is E^-1 K.
  EXPECT_TRUE((e * t.keyframes[0].pose).isApprox(k.odom_pose, 1e-12));
  EXPECT_EQ(t.keyframes[0].voxel_size, 1.5);
  EXPECT_EQ(t.keyframes[0].distributions.size(), 3u);
  // Without a twist or an interval: no motion known.
  seed.interval_s = 0.0;
  EXPECT_TRUE(tracker_seed(seed, seconds(100.5), 10.0, e)
                  .velocity.isApprox(Eigen::Isometry3d::Identity(), 0.0));
}

TEST(StreamProcessor, TakenOverWithMapPatchesContinuesTheOldOwnersTrack) {
  // The old owner tracks frames 0..9 of a known motion; its last odometry and keyframes are
  // the seed. The new owner gets frames 12.. (two lost in the handover) and must continue on
  // the old owner's track, registering its first frame against the patches' map.
  const PointCloud scene = litamin2::testing::synthetic_scene(1, 30000);
  auto truth = [](int i) {
    Eigen::Isometry3d sensor = Eigen::Isometry3d::Identity();
    sensor.translation() = Eigen::Vector3d(0.6 * i, 0.02 * i * i, 0.0);
    sensor.linear() = Eigen::AngleAxisd(0.015 * i, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    return sensor;
  };
  auto frame = [&](int i) {
    Frame f;
    f.cloud = litamin2::testing::transformed(scene, truth(i).inverse());
    f.sequence = static_cast<std::uint64_t>(i);
    f.stamp = seconds(100.0 + 0.1 * i);
    f.arrival = std::chrono::steady_clock::now();
    return f;
  };
  StreamConfig config;
  config.id = "car1";
  KeyframeSink old_sink;
  StreamStats old_stats;
  StreamProcessor old_owner(config, old_sink, old_stats);
  for (int i = 0; i < 10; ++i) {
    Frame f = frame(i);
    old_owner.process(f);
  }
  ASSERT_GE(old_sink.keyframes.size(), 3u);
  const OdometryOutput& last = old_sink.odometry.back();
  ASSERT_TRUE(last.twist.has_value());
  HandoverSeed seed;
  seed.pose = last.pose;
  seed.stamp = last.stamp;
  seed.twist = last.twist->twist;
  seed.interval_s = 0.1;
  seed.next_keyframe_id = old_sink.keyframes.back().key.id + 1;
  seed.map_keyframes = select_map_seed(old_sink.keyframes, last.stamp, MapSeedLimits{3, 10.0});
  KeyframeSink new_sink;
  StreamStats new_stats;
  StreamProcessor new_owner(config, new_sink, new_stats, seed, 10.0);
  for (int i = 12; i < 18; ++i) {
    Frame f = frame(i);
    new_owner.process(f);
  }
  EXPECT_TRUE(new_owner.continued());
  EXPECT_FALSE(new_owner.origin().has_value());
  ASSERT_EQ(new_sink.odometry.size(), 6u);
  EXPECT_TRUE(new_sink.odometry.front().registered);
  for (std::size_t j = 0; j < new_sink.odometry.size(); ++j) {
    const Eigen::Isometry3d expected = truth(12 + static_cast<int>(j));
    const Eigen::Isometry3d error = expected.inverse() * new_sink.odometry[j].pose;
    EXPECT_LT(error.translation().norm(), 0.05) << j;
    EXPECT_LT(Eigen::AngleAxisd(error.linear()).angle(), 0.2 * M_PI / 180.0) << j;
  }
  ASSERT_FALSE(new_sink.keyframes.empty());
  EXPECT_EQ(new_sink.keyframes.front().key.id, seed.next_keyframe_id);
}

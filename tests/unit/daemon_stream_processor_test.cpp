// Per-frame processing of a stream: poses equal a plain Tracker's bit for bit, keyframes are
// published with their distributions, the extrinsic moves poses and covariances to the base.

#include "litamin2/daemon/stream_processor.hpp"
#include "support/synthetic_scene.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <optional>
#include <vector>

using namespace litamin2;
using namespace litamin2::daemon;

namespace {

struct Recorded {
  std::string stream;
  Eigen::Isometry3d pose;
  Matrix6d covariance;
  bool keyframe;
  std::uint64_t sequence;
  Stamp stamp;
  std::optional<TwistEstimate> twist;
  bool registered;
};

class RecordingSink : public ResultSink {
 public:
  void publish_odometry(const OdometryOutput& o) override {
    odometry.push_back(
        {o.stream, o.pose, o.covariance, o.keyframe, o.sequence, o.stamp, o.twist, o.registered});
  }
  void publish_keyframe(const Keyframe& k) override {
    keyframe_ids.push_back(k.key.id);
    keyframe_poses.push_back(k.odom_pose);
    keyframe_sizes.push_back(k.distributions.size());
    voxel_size = k.voxel_size;
  }
  std::vector<Recorded> odometry;
  std::vector<std::uint64_t> keyframe_ids;
  std::vector<Eigen::Isometry3d> keyframe_poses;
  std::vector<std::size_t> keyframe_sizes;
  double voxel_size = 0;
};

std::vector<PointCloud> scans(int n) {
  const PointCloud scene = litamin2::testing::synthetic_scene(1, 30000);
  std::vector<PointCloud> out;
  for (int i = 0; i < n; ++i) {
    // The sensor moves 0.6 m forward per frame and turns slightly: the scene moves back.
    Eigen::Isometry3d sensor = Eigen::Isometry3d::Identity();
    sensor.translation() = Eigen::Vector3d(0.6 * i, 0.05 * i, 0.0);
    sensor.linear() = Eigen::AngleAxisd(0.01 * i, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    out.push_back(litamin2::testing::transformed(scene, sensor.inverse()));
  }
  return out;
}

Frame frame_of(const PointCloud& cloud, std::uint64_t sequence) {
  Frame f;
  f.cloud = cloud;
  f.sequence = sequence;
  f.stamp = Stamp{static_cast<std::int64_t>(100 + sequence) * 1'000'000'000 + 5000};
  f.arrival = std::chrono::steady_clock::now();
  return f;
}

}  // namespace

TEST(StreamProcessor, PosesEqualThePlainTrackerBitForBit) {
  const std::vector<PointCloud> input = scans(6);
  StreamConfig config;
  config.id = "car1";
  RecordingSink sink;
  StreamStats stats;
  StreamProcessor processor(config, sink, stats);
  Tracker reference(config.tracker);
  for (std::size_t i = 0; i < input.size(); ++i) {
    Frame f = frame_of(input[i], i);
    processor.process(f);
    const FrameResult expected = reference.process(input[i]);
    ASSERT_EQ(sink.odometry.size(), i + 1);
    const Recorded& r = sink.odometry.back();
    EXPECT_EQ(r.stream, "car1");
    EXPECT_EQ(r.sequence, i);
    EXPECT_EQ(r.stamp.nanoseconds, static_cast<std::int64_t>(100 + i) * 1'000'000'000 + 5000);
    EXPECT_EQ(r.keyframe, expected.keyframe);
    EXPECT_TRUE((r.pose.matrix().array() == expected.pose.matrix().array()).all()) << i;
    EXPECT_TRUE((r.covariance.array() == expected.covariance.array()).all()) << i;
  }
  // The sensor moved 3 m: the first frame and at least one more are keyframes.
  ASSERT_GE(sink.keyframe_ids.size(), 2u);
  for (std::size_t k = 0; k < sink.keyframe_ids.size(); ++k) EXPECT_EQ(sink.keyframe_ids[k], k);
  EXPECT_EQ(processor.keyframes(), sink.keyframe_ids.size());
  for (std::size_t n : sink.keyframe_sizes) EXPECT_GT(n, 0u);
  EXPECT_EQ(sink.voxel_size, config.tracker.voxelizer.voxel_size);
  EXPECT_TRUE(
      sink.odometry.back().pose.translation().isApprox(Eigen::Vector3d(3.0, 0.25, 0.0), 0.02));
  const StatsSnapshot s = stats.snapshot();
  EXPECT_EQ(s.frames_processed, 6u);
  EXPECT_EQ(s.keyframes, sink.keyframe_ids.size());
  EXPECT_GT(s.map_size, 0u);
  EXPECT_GT(s.latency_p50_ms, 0.0);
}

TEST(StreamProcessor, ExtrinsicGivesTheBasePose) {
  const std::vector<PointCloud> input = scans(3);
  StreamConfig config;
  config.id = "car2";
  config.extrinsic.translation() = Eigen::Vector3d(1.5, 0.0, 1.8);
  config.extrinsic.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  RecordingSink sink;
  StreamStats stats;
  StreamProcessor processor(config, sink, stats);
  Tracker reference(config.tracker);
  for (std::size_t i = 0; i < input.size(); ++i) {
    Frame f = frame_of(input[i], i);
    processor.process(f);
    const FrameResult expected = reference.process(input[i]);
    const Eigen::Isometry3d base = base_pose(expected.pose, config.extrinsic);
    EXPECT_TRUE(sink.odometry.back().pose.isApprox(base, 1e-12));
    EXPECT_TRUE(sink.odometry.back().covariance.isApprox(
        transform_left_covariance(expected.covariance, config.extrinsic), 1e-12));
  }
  // A keyframe's pose is the sensor's pose in the odometry frame.
  EXPECT_TRUE(sink.keyframe_poses.front().isApprox(config.extrinsic, 1e-12));
}

TEST(StreamProcessor, DeskewingStreamUsesTheStampsAndSurvivesAPublisherRestart) {
  // Scans with per-point times (here every point at 0.04 s: the times reach the tracker when
  // they change the poses) and a stamp going back after frame 4, as a restarted publisher's.
  std::vector<PointCloud> input = scans(8);
  for (PointCloud& c : input) c.times.assign(c.size(), 0.04f);
  StreamConfig config;
  config.id = "car1";
  config.tracker.deskew.enabled = true;
  RecordingSink sink;
  StreamStats stats;
  StreamProcessor processor(config, sink, stats);
  Tracker reference(config.tracker);
  Tracker untimed(config.tracker);
  bool differs = false;
  for (std::size_t i = 0; i < input.size(); ++i) {
    Frame f = frame_of(input[i], i);
    if (i >= 5) f.stamp.nanoseconds -= 3'000'000'000;  // restarted at 5, 100 ms apart again
    ASSERT_NO_THROW(processor.process(f)) << i;
    if (i == 5) reference.restart_clock();
    const FrameResult expected = reference.process(input[i], SweepTiming{f.stamp});
    EXPECT_TRUE(expected.deskewed);
    const FrameResult plain = untimed.process(input[i]);
    differs = differs || !plain.pose.isApprox(expected.pose, 1e-12);
    ASSERT_EQ(sink.odometry.size(), i + 1);
    EXPECT_EQ(0, std::memcmp(sink.odometry.back().pose.matrix().data(),
                             expected.pose.matrix().data(), 16 * sizeof(double)))
        << i;
  }
  EXPECT_TRUE(differs) << "the per-point times did not reach the tracker";
}

TEST(StreamProcessor, TwistIsTheBodyVelocityOfTheKnownMotion) {
  // scans(): per frame (1 s apart) the sensor turns 0.01 rad about z and moves (0.6, 0.05, 0)
  // in the first frame's axes; with an extrinsic the base's twist is published, in its frame.
  const std::vector<PointCloud> input = scans(5);
  StreamConfig config;
  config.id = "car3";
  config.extrinsic.translation() = Eigen::Vector3d(1.0, 0.0, 1.5);
  config.extrinsic.linear() = Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  RecordingSink sink;
  StreamStats stats;
  StreamProcessor processor(config, sink, stats);
  auto truth = [](int i) {
    Eigen::Isometry3d sensor = Eigen::Isometry3d::Identity();
    sensor.translation() = Eigen::Vector3d(0.6 * i, 0.05 * i, 0.0);
    sensor.linear() = Eigen::AngleAxisd(0.01 * i, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    return sensor;
  };
  for (std::size_t i = 0; i < input.size(); ++i) {
    Frame f = frame_of(input[i], i);
    processor.process(f);
  }
  ASSERT_EQ(sink.odometry.size(), input.size());
  EXPECT_FALSE(sink.odometry[0].twist) << "no twist without a previous frame";
  for (std::size_t i = 1; i < input.size(); ++i) {
    const Recorded& r = sink.odometry[i];
    ASSERT_TRUE(r.registered) << i;
    ASSERT_TRUE(r.twist) << i;
    // Exactly the twist between the published poses over the stamps' interval (1 s) ...
    const TwistEstimate expected =
        twist_between(sink.odometry[i - 1].pose, r.pose, r.covariance, 1.0);
    EXPECT_EQ(r.twist->twist.linear, expected.twist.linear);
    EXPECT_EQ(r.twist->twist.angular, expected.twist.angular);
    EXPECT_TRUE(r.twist->covariance.isApprox(expected.covariance, 0.0));
    // ... which is the base's true body velocity, to the registration's accuracy.
    const Eigen::Isometry3d motion =
        base_pose(truth(static_cast<int>(i) - 1), config.extrinsic).inverse() *
        base_pose(truth(static_cast<int>(i)), config.extrinsic);
    const Twist true_twist = twist_from_motion(motion, 1.0);
    EXPECT_LT((r.twist->twist.linear - true_twist.linear).norm(), 0.02) << i;
    EXPECT_LT((r.twist->twist.angular - true_twist.angular).norm(), 2e-3) << i;
    // A registered frame has a covariance, hence a positive twist variance on every axis.
    for (int k = 0; k < 6; ++k) EXPECT_GT(r.twist->covariance(k, k), 0.0) << i << " " << k;
  }
}

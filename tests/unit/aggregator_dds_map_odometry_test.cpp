// A vehicle's current pose in the map frame (aggregator/dds/map_odometry.hpp): the composition
// corrected keyframe * inverse(keyframe odometry) * latest odometry on known transforms (a wrong
// order or inverse fails), the message's frames, covariance and twist, and the relay's
// behaviour before the first keyframe and with its counters.

#include "litamin2/aggregator/dds/map_odometry.hpp"
#include "litamin2/aggregator/dds/map_odometry_relay.hpp"
#include "litamin2/dds/odometry_conversion.hpp"
#include "litamin2/dds/pose_conversion.hpp"
#include "litamin2/dds/transform_conversion.hpp"

#include <gtest/gtest.h>

#include <thread>
#include <vector>

using namespace litamin2;
using namespace litamin2::aggregator;

namespace {

Eigen::Isometry3d pose_of(double x, double y, double z, double yaw) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  pose.translation() = Eigen::Vector3d(x, y, z);
  return pose;
}

nav_msgs::msg::Odometry odometry_at(const Eigen::Isometry3d& pose, const Matrix6d& left) {
  nav_msgs::msg::Odometry msg =
      dds::to_odometry(pose, left, Stamp::from_seconds(12.5), "odom", "car/base_link");
  msg.twist().twist().linear().x(7.0);
  msg.twist().twist().angular().z(0.25);
  return msg;
}

}  // namespace

TEST(AggregatorMapOdometry, ComposesCorrectedKeyframeWithOdometrySinceIt) {
  // The keyframe: in the odometry frame at (10, 0, 0) heading +y; the mapper corrected it to
  // (100, 50, 0) heading -x (a 90 deg turn more). Since the keyframe the vehicle drove 5 m
  // straight ahead and turned 30 deg left: in the map frame it is 5 m along -x from the
  // corrected keyframe, at (95, 50, 0), heading -x turned 30 deg left.
  const Eigen::Isometry3d keyframe_odom = pose_of(10, 0, 0, M_PI / 2);
  const Eigen::Isometry3d keyframe_corrected = pose_of(100, 50, 0, M_PI);
  const Eigen::Isometry3d odom = keyframe_odom * pose_of(5, 0, 0, M_PI / 6);
  ASSERT_TRUE(odom.translation().isApprox(Eigen::Vector3d(10, 5, 0), 1e-12));

  const MapCorrection c{odometry_correction(keyframe_corrected, keyframe_odom), "map"};
  const nav_msgs::msg::Odometry out = to_map_odometry(odometry_at(odom, Matrix6d::Zero()), c);
  const Eigen::Isometry3d pose = dds::from_pose_msg(out.pose().pose());
  EXPECT_LT((pose.translation() - Eigen::Vector3d(95, 50, 0)).norm(), 1e-9);
  const double yaw = std::atan2(pose.linear()(1, 0), pose.linear()(0, 0));
  EXPECT_NEAR(yaw, -M_PI + M_PI / 6, 1e-9);
  EXPECT_EQ(out.header().frame_id(), "map");
  EXPECT_EQ(out.child_frame_id(), "car/base_link");
  EXPECT_EQ(out.header().stamp().sec(), 12);
  EXPECT_EQ(out.header().stamp().nanosec(), 500'000'000u);
  // The twist is in the child frame: unchanged.
  EXPECT_DOUBLE_EQ(out.twist().twist().linear().x(), 7.0);
  EXPECT_DOUBLE_EQ(out.twist().twist().angular().z(), 0.25);
}

TEST(AggregatorMapOdometry, CovarianceTurnsWithTheCorrection) {
  // Position uncertainty only along the odometry frame's x; the correction turns that frame by
  // 90 deg about z (and moves it): in the map frame the uncertainty is along y.
  Matrix6d left = Matrix6d::Zero();
  left(3, 3) = 0.04;  // tau_x
  left(4, 4) = 1e-6;
  left(5, 5) = 1e-6;
  const Eigen::Isometry3d odom = Eigen::Isometry3d::Identity();
  const MapCorrection c{pose_of(0, 0, 0, M_PI / 2), "map"};
  const nav_msgs::msg::Odometry out = to_map_odometry(odometry_at(odom, left), c);
  const auto& cov = out.pose().covariance();  // ROS order: x, y, z, rx, ry, rz; row-major
  EXPECT_NEAR(cov[0 * 6 + 0], 1e-6, 1e-12);
  EXPECT_NEAR(cov[1 * 6 + 1], 0.04, 1e-12);
  EXPECT_NEAR(cov[2 * 6 + 2], 1e-6, 1e-12);
}

TEST(AggregatorMapOdometry, MapCorrectionFrameFollowsTheMerge) {
  StreamPoses poses;
  poses.stream = "car_2";
  poses.anchor = "car_2";
  poses.correction = pose_of(1, 2, 3, 0.5);
  EXPECT_EQ(map_correction(poses).frame_id, "car_2/odom");
  poses.anchor = "car_1";
  poses.in_map_frame = true;
  const MapCorrection c = map_correction(poses);
  EXPECT_EQ(c.frame_id, "map");
  EXPECT_TRUE(c.correction.isApprox(poses.correction, 0.0));
}

TEST(AggregatorMapOdometryRelay, NothingBeforeTheFirstKeyframeThenTheLatest) {
  MapOdometryRelay relay;
  std::vector<nav_msgs::msg::Odometry> published;
  relay.add_stream("car", [&](const nav_msgs::msg::Odometry& m) { published.push_back(m); });
  using Clock = MapOdometryRelay::Clock;
  const Clock::time_point t0 = Clock::now();
  const Matrix6d zero = Matrix6d::Zero();

  relay.offer("car", odometry_at(pose_of(1, 0, 0, 0), zero), t0);
  relay.flush();
  EXPECT_TRUE(published.empty());  // no keyframe yet: no correction

  relay.set_correction("car", {pose_of(0, 10, 0, 0), "map"});
  // Two messages before the publisher runs: only the latest is published.
  relay.offer("car", odometry_at(pose_of(2, 0, 0, 0), zero), t0 + std::chrono::milliseconds(100));
  relay.offer("car", odometry_at(pose_of(3, 0, 0, 0), zero), t0 + std::chrono::milliseconds(200));
  relay.flush();
  ASSERT_EQ(published.size(), 1u);
  const Eigen::Vector3d p = dds::from_pose_msg(published[0].pose().pose()).translation();
  EXPECT_LT((p - Eigen::Vector3d(3, 10, 0)).norm(), 1e-12);
  relay.flush();
  EXPECT_EQ(published.size(), 1u);

  // 11 messages over 1 s: 10 Hz.
  for (int i = 1; i <= 10; ++i)
    relay.offer("car", odometry_at(pose_of(3, 0, 0, 0), zero),
                t0 + std::chrono::milliseconds(200 + 100 * i));
  const auto s = relay.status(t0 + std::chrono::milliseconds(1500)).at("car");
  EXPECT_EQ(s.received, 13u);
  EXPECT_EQ(s.before_keyframe, 1u);
  EXPECT_EQ(s.published, 1u);
  EXPECT_NEAR(s.rate_hz, 10.0, 1e-9);
  EXPECT_NEAR(s.last_seen_s, 0.3, 1e-9);
  EXPECT_EQ(s.frame_id, "map");
  // Silent for longer than the rate window: rate 0.
  EXPECT_EQ(relay.status(t0 + std::chrono::seconds(5)).at("car").rate_hz, 0.0);
}

TEST(AggregatorMapOdometryRelay, PublishesFromItsThreadAndDrainsOnStop) {
  MapOdometryRelay relay;
  std::atomic<int> published{0};
  relay.add_stream("car", [&](const nav_msgs::msg::Odometry&) { ++published; });
  relay.set_correction("car", {Eigen::Isometry3d::Identity(), "map"});
  relay.start();
  relay.offer("car", odometry_at(pose_of(1, 0, 0, 0), Matrix6d::Zero()));
  relay.stop();
  EXPECT_EQ(published.load(), 1);
  EXPECT_EQ(relay.status().at("car").published, 1u);
}

TEST(AggregatorMapOdometry, MapTransformIsTheCorrectionFromMapToTheOdometryFrame) {
  const Matrix6d zero = Matrix6d::Zero();
  const MapCorrection c{pose_of(4, -2, 0.5, 0.3), "map"};
  const nav_msgs::msg::Odometry odom = odometry_at(pose_of(3, 1, 0, 0.1), zero);
  const auto tf = to_map_transform(odom, c);
  ASSERT_TRUE(tf);
  EXPECT_EQ(tf->header().frame_id(), "map");
  EXPECT_EQ(tf->child_frame_id(), "odom");  // the odometry's frame_id
  EXPECT_EQ(tf->header().stamp().sec(), odom.header().stamp().sec());
  EXPECT_EQ(tf->header().stamp().nanosec(), odom.header().stamp().nanosec());
  // map -> odom composed with odom -> base is the map-frame pose the relay publishes.
  const Eigen::Isometry3d composed =
      dds::from_transform_msg(tf->transform()) * dds::from_pose_msg(odom.pose().pose());
  const Eigen::Isometry3d in_map = dds::from_pose_msg(to_map_odometry(odom, c).pose().pose());
  EXPECT_TRUE(composed.isApprox(in_map, 1e-12));
  EXPECT_LT(
      (dds::from_transform_msg(tf->transform()).translation() - Eigen::Vector3d(4, -2, 0.5)).norm(),
      1e-12);
  // A stream that is its own group's anchor (frame "<anchor>/odom" = its odometry frame): no
  // transform of a frame to itself.
  EXPECT_FALSE(to_map_transform(odom, MapCorrection{Eigen::Isometry3d::Identity(), "odom"}));
}

TEST(AggregatorMapOdometryRelay, PublishesTheMapTransformWithEachPose) {
  MapOdometryRelay relay;
  std::vector<nav_msgs::msg::Odometry> published;
  std::vector<geometry_msgs::msg::TransformStamped> transforms;
  relay.add_stream(
      "car", [&](const nav_msgs::msg::Odometry& m) { published.push_back(m); },
      [&](const geometry_msgs::msg::TransformStamped& t) { transforms.push_back(t); });
  relay.offer("car", odometry_at(pose_of(1, 0, 0, 0), Matrix6d::Zero()));
  relay.flush();
  EXPECT_TRUE(transforms.empty());  // no correction yet
  relay.set_correction("car", {pose_of(0, 10, 0, 0), "map"});
  relay.offer("car", odometry_at(pose_of(2, 0, 0, 0), Matrix6d::Zero()));
  relay.flush();
  relay.set_correction("car", {pose_of(0, 11, 0, 0), "map"});
  relay.offer("car", odometry_at(pose_of(3, 0, 0, 0), Matrix6d::Zero()));
  relay.flush();
  ASSERT_EQ(published.size(), 2u);
  ASSERT_EQ(transforms.size(), 2u);
  EXPECT_DOUBLE_EQ(transforms[0].transform().translation().y(), 10.0);
  EXPECT_DOUBLE_EQ(transforms[1].transform().translation().y(), 11.0);  // the new correction
  EXPECT_EQ(transforms[1].header().frame_id(), "map");
}

TEST(AggregatorMapOdometryRelay, AChangedCorrectionSendsItsTransformWithoutANewPose) {
  MapOdometryRelay relay;
  int poses = 0;
  std::vector<geometry_msgs::msg::TransformStamped> transforms;
  relay.add_stream(
      "car", [&](const nav_msgs::msg::Odometry&) { ++poses; },
      [&](const geometry_msgs::msg::TransformStamped& t) { transforms.push_back(t); });
  // The stream's odometry stopped before its first keyframe reached the mapper.
  relay.offer("car", odometry_at(pose_of(1, 0, 0, 0), Matrix6d::Zero()));
  relay.flush();
  relay.set_correction("car", {pose_of(0, 10, 0, 0), "map"});
  relay.flush();
  ASSERT_EQ(transforms.size(), 1u);
  EXPECT_EQ(poses, 0);  // map_odom waits for a pose; the transform does not
  EXPECT_DOUBLE_EQ(transforms[0].transform().translation().y(), 10.0);
  EXPECT_EQ(transforms[0].header().stamp().sec(), 12);  // the latest odometry's stamp
  EXPECT_EQ(transforms[0].header().stamp().nanosec(), 500000000u);
  EXPECT_EQ(transforms[0].child_frame_id(), "odom");
  // The same correction again (poses republished for other keyframes): nothing new.
  relay.set_correction("car", {pose_of(0, 10, 0, 0), "map"});
  relay.flush();
  EXPECT_EQ(transforms.size(), 1u);
  // A loop moved it, still without a new pose: not at the same stamp again (tf2 ignores a
  // repeated stamp); the next pose carries it.
  relay.set_correction("car", {pose_of(0, 10.5, 0, 0), "map"});
  relay.flush();
  EXPECT_EQ(transforms.size(), 1u);
  nav_msgs::msg::Odometry later = odometry_at(pose_of(2, 0, 0, 0), Matrix6d::Zero());
  later.header().stamp().sec(13);
  relay.offer("car", later);
  relay.flush();
  ASSERT_EQ(transforms.size(), 2u);
  EXPECT_DOUBLE_EQ(transforms[1].transform().translation().y(), 10.5);
  EXPECT_EQ(transforms[1].header().stamp().sec(), 13);
  // Moved again after that pose: sent at once, at the latest stamp (13) only if unused: not.
  relay.set_correction("car", {pose_of(0, 11, 0, 0), "map"});
  relay.flush();
  EXPECT_EQ(transforms.size(), 2u);
  EXPECT_EQ(poses, 1);
}

TEST(AggregatorMapOdometryRelay, MapFrameOutputsWaitForTheSettlingThenCarryTheLatestCorrection) {
  // Two vehicles start together; car_b's first patch arrived first, so for a moment the map
  // frame is car_b's odometry frame. Nothing in the map frame may go out before the settling
  // ends; then the corrections of that time (car_b no longer in the map frame) are used.
  using namespace std::chrono_literals;
  MapOdometryRelay relay(300ms);
  std::vector<nav_msgs::msg::Odometry> a_out, b_out;
  relay.add_stream("car_a", [&](const nav_msgs::msg::Odometry& m) { a_out.push_back(m); });
  relay.add_stream("car_b", [&](const nav_msgs::msg::Odometry& m) { b_out.push_back(m); });
  const Matrix6d zero = Matrix6d::Zero();
  relay.set_correction("car_b", {pose_of(0, 0, 0, 0), "map"});
  relay.offer("car_b", odometry_at(pose_of(1, 0, 0, 0), zero));
  relay.flush();
  EXPECT_TRUE(b_out.empty());  // held: the map frame is not settled
  relay.set_correction("car_a", {pose_of(0, 0, 0, 0), "map"});
  relay.set_correction("car_b", {pose_of(0, 0, 0, 0), "car_b/odom"});
  relay.offer("car_a", odometry_at(pose_of(2, 0, 0, 0), zero));
  relay.flush();
  // car_b's frame is its own now: not held; car_a's (map) still is.
  ASSERT_EQ(b_out.size(), 1u);
  EXPECT_EQ(b_out[0].header().frame_id(), "car_b/odom");
  EXPECT_TRUE(a_out.empty());
  relay.start();  // its thread publishes what was held once the settling ends
  const auto deadline = std::chrono::steady_clock::now() + 5s;
  while (std::chrono::steady_clock::now() < deadline) {
    if (relay.status().at("car_a").published == 1) break;
    std::this_thread::sleep_for(10ms);
  }
  relay.stop();
  ASSERT_EQ(a_out.size(), 1u);
  EXPECT_EQ(a_out[0].header().frame_id(), "map");
  for (const auto& m : b_out) EXPECT_NE(m.header().frame_id(), "map");
}

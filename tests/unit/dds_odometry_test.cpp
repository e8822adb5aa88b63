/// Odometry conversion: pose, covariance reordering (left update -> ROS order) and back.

#include <gtest/gtest.h>

#include <limits>

#include <random>

#include "litamin2/core/so3.hpp"
#include "litamin2/dds/odometry_conversion.hpp"
#include "litamin2/dds/pose_conversion.hpp"

namespace litamin2::dds {
namespace {

Eigen::Isometry3d some_pose() {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  pose.translation() = Eigen::Vector3d(10.0, -4.0, 2.5);
  return pose;
}

Matrix6d random_covariance(unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0.0, 1.0);
  Matrix6d a;
  for (int i = 0; i < 36; ++i) a(i / 6, i % 6) = n(rng);
  return a * a.transpose() * 1e-3 + Matrix6d::Identity() * 1e-6;
}

TEST(DdsOdometry, PoseRoundTrip) {
  const Eigen::Isometry3d pose = some_pose();
  const Eigen::Isometry3d back = from_pose_msg(to_pose_msg(pose));
  EXPECT_TRUE(back.isApprox(pose, 1e-12));
  EXPECT_GE(to_pose_msg(pose).orientation().w(), 0.0);
  EXPECT_FALSE(pose_msg_error(to_pose_msg(pose)));
  // A zero or unnormalised quaternion is not a pose: rejected, not replaced or normalised.
  geometry_msgs::msg::Pose zero;
  zero.orientation().w(0.0);
  ASSERT_TRUE(pose_msg_error(zero));
  EXPECT_NE(pose_msg_error(zero)->find("not a unit quaternion (norm 0)"), std::string::npos);
  geometry_msgs::msg::Pose twice = to_pose_msg(pose);
  twice.orientation().w(2.0 * twice.orientation().w());
  EXPECT_TRUE(pose_msg_error(twice));
}

TEST(DdsOdometry, AtOriginTheCovarianceBlocksAreSwapped) {
  Matrix6d left = Matrix6d::Zero();
  left.block<3, 3>(0, 0) = Eigen::Vector3d(1, 2, 3).asDiagonal();     // rotation (phi)
  left.block<3, 3>(3, 3) = Eigen::Vector3d(10, 20, 30).asDiagonal();  // translation (tau)
  left(0, 3) = left(3, 0) = 0.5;                                      // phi_x / tau_x
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = some_pose().linear();  // rotation does not matter, only the position
  const auto ros = ros_pose_covariance(left, pose);
  // Row-major, (x, y, z, rx, ry, rz).
  EXPECT_DOUBLE_EQ(ros[0 * 6 + 0], 10.0);
  EXPECT_DOUBLE_EQ(ros[1 * 6 + 1], 20.0);
  EXPECT_DOUBLE_EQ(ros[2 * 6 + 2], 30.0);
  EXPECT_DOUBLE_EQ(ros[3 * 6 + 3], 1.0);
  EXPECT_DOUBLE_EQ(ros[4 * 6 + 4], 2.0);
  EXPECT_DOUBLE_EQ(ros[5 * 6 + 5], 3.0);
  EXPECT_DOUBLE_EQ(ros[0 * 6 + 3], 0.5);  // x / rx
  EXPECT_DOUBLE_EQ(ros[3 * 6 + 0], 0.5);
  EXPECT_DOUBLE_EQ(ros[1 * 6 + 3], 0.0);
}

TEST(DdsOdometry, CovarianceMatchesSampledPerturbations) {
  // Perturb a pose by samples of the left update and compare the sample covariance of
  // (position, fixed-axis rotation) with the converted covariance.
  const Eigen::Isometry3d pose = some_pose();
  const Matrix6d left = random_covariance(3) * 1e-3;
  const Eigen::LLT<Matrix6d> llt(left);
  const Matrix6d l = llt.matrixL();
  std::mt19937 rng(5);
  std::normal_distribution<double> n(0.0, 1.0);
  const int samples = 200000;
  Matrix6d sum = Matrix6d::Zero();
  for (int s = 0; s < samples; ++s) {
    Eigen::Matrix<double, 6, 1> z;
    for (int i = 0; i < 6; ++i) z[i] = n(rng);
    const Eigen::Matrix<double, 6, 1> xi = l * z;
    const Eigen::Isometry3d moved = apply_left_update(xi, pose);
    Eigen::Matrix<double, 6, 1> d;
    d.head<3>() = moved.translation() - pose.translation();
    const Eigen::AngleAxisd delta(moved.linear() * pose.linear().transpose());
    d.tail<3>() = delta.angle() * delta.axis();
    sum += d * d.transpose();
  }
  const Matrix6d sampled = sum / samples;
  const auto ros = ros_pose_covariance(left, pose);
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) {
      const double scale = std::sqrt(sampled(r, r) * sampled(c, c));
      EXPECT_NEAR(ros[static_cast<std::size_t>(6 * r + c)], sampled(r, c), 0.03 * scale)
          << r << "," << c;
    }
  }
}

TEST(DdsOdometry, CovarianceRoundTrip) {
  const Eigen::Isometry3d pose = some_pose();
  const Matrix6d left = random_covariance(9);
  const Matrix6d back = left_covariance_from_ros(ros_pose_covariance(left, pose), pose);
  EXPECT_TRUE(back.isApprox(left, 1e-12));
}

TEST(DdsOdometry, MessageRoundTrip) {
  const Eigen::Isometry3d pose = some_pose();
  const Matrix6d left = random_covariance(11);
  const auto msg = to_odometry(pose, left, Stamp::from_seconds(1234.5), "car1/odom", "car1");
  EXPECT_EQ(msg.header().frame_id(), "car1/odom");
  EXPECT_EQ(msg.child_frame_id(), "car1");
  EXPECT_EQ(msg.header().stamp().sec(), 1234);
  EXPECT_EQ(msg.header().stamp().nanosec(), 500000000u);
  EXPECT_DOUBLE_EQ(msg.pose().pose().position().x(), 10.0);
  EXPECT_DOUBLE_EQ(msg.twist().covariance()[0], -1.0);
  EXPECT_DOUBLE_EQ(msg.twist().covariance()[35], -1.0);
  const OdometryConversion converted = from_odometry(msg);
  ASSERT_TRUE(converted.ok()) << converted.message;
  const OdometrySample& sample = converted.sample;
  EXPECT_EQ(sample.stamp.nanoseconds, 1'234'500'000'000);
  EXPECT_EQ(sample.frame_id, "car1/odom");
  EXPECT_EQ(sample.child_frame_id, "car1");
  EXPECT_TRUE(sample.pose.isApprox(pose, 1e-12));
  EXPECT_TRUE(sample.left_covariance.isApprox(left, 1e-9));
  // ros_covariance is the message's array as a row-major matrix.
  EXPECT_DOUBLE_EQ(sample.ros_covariance(0, 5), msg.pose().covariance()[5]);
  EXPECT_DOUBLE_EQ(sample.ros_covariance(5, 0), msg.pose().covariance()[30]);
}

TEST(DdsOdometry, TwistGoesInLinearFirstWithItsCovariance) {
  // The twist of a known motion (0.1 s at 8 m/s forward, 0.4 rad/s yaw) in the child frame.
  Twist body;
  body.linear = Eigen::Vector3d(8.0, 0.3, -0.1);
  body.angular = Eigen::Vector3d(0.02, -0.01, 0.4);
  const Eigen::Isometry3d previous = some_pose();
  const Eigen::Isometry3d pose = previous * motion_after(body, 0.1);
  const TwistEstimate twist = twist_between(previous, pose, random_covariance(13), 0.1);
  const auto msg = to_odometry(pose, random_covariance(13), Stamp::from_seconds(10.0), "odom",
                               "base_link", twist);
  const auto& t = msg.twist().twist();
  EXPECT_NEAR(t.linear().x(), 8.0, 1e-9);
  EXPECT_NEAR(t.linear().y(), 0.3, 1e-9);
  EXPECT_NEAR(t.linear().z(), -0.1, 1e-9);
  EXPECT_NEAR(t.angular().x(), 0.02, 1e-9);
  EXPECT_NEAR(t.angular().y(), -0.01, 1e-9);
  EXPECT_NEAR(t.angular().z(), 0.4, 1e-9);
  // ROS order (vx, vy, vz, wx, wy, wz): the estimate's (angular, linear) blocks swapped.
  const auto& cov = msg.twist().covariance();
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) {
      EXPECT_EQ(cov[static_cast<std::size_t>(6 * r + c)],
                twist.covariance((r + 3) % 6, (c + 3) % 6))
          << r << "," << c;
    }
  }
  for (int i = 0; i < 6; ++i) EXPECT_GT(cov[static_cast<std::size_t>(7 * i)], 0.0) << i;
  EXPECT_TRUE(from_odometry(msg).ok());
}

TEST(DdsOdometry, ZeroCovarianceStaysZero) {
  const auto msg = to_odometry(some_pose(), Matrix6d::Zero(), Stamp{}, "odom", "base");
  for (double v : msg.pose().covariance()) EXPECT_EQ(v, 0.0);
}

TEST(DdsOdometry, RejectsBadMessages) {
  const auto good = to_odometry(some_pose(), random_covariance(3), Stamp{5}, "odom", "base");
  ASSERT_TRUE(from_odometry(good).ok());
  auto m = good;
  m.pose().pose().position().y(std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(from_odometry(m).error, OdometryError::kBadPose);
  m = good;
  m.pose().pose().orientation().x(0.0);
  m.pose().pose().orientation().y(0.0);
  m.pose().pose().orientation().z(0.0);
  m.pose().pose().orientation().w(0.0);
  EXPECT_EQ(from_odometry(m).error, OdometryError::kBadPose);
  EXPECT_NE(from_odometry(m).message.find("not a unit quaternion"), std::string::npos);
  m = good;
  m.pose().covariance()[7] = std::numeric_limits<double>::infinity();
  EXPECT_EQ(from_odometry(m).error, OdometryError::kBadCovariance);
  m = good;
  m.pose().covariance()[0] = -1.0;  // a negative variance
  EXPECT_EQ(from_odometry(m).error, OdometryError::kBadCovariance);
  EXPECT_NE(from_odometry(m).message.find("positive semi-definite"), std::string::npos);
  m = good;
  m.pose().pose().position().x(1e200);
  EXPECT_EQ(from_odometry(m).error, OdometryError::kBadPose);
  m = good;
  m.twist().twist().linear().x(std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(from_odometry(m).error, OdometryError::kBadTwist);
  m = good;
  m.header().stamp().nanosec(1'000'000'000u);
  EXPECT_EQ(from_odometry(m).error, OdometryError::kBadStamp);
  EXPECT_STREQ(to_string(OdometryError::kBadStamp), "bad_stamp");
}

}  // namespace
}  // namespace litamin2::dds

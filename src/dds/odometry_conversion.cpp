#include "litamin2/dds/odometry_conversion.hpp"

#include "litamin2/core/so3.hpp"
#include "litamin2/core/value_checks.hpp"
#include "litamin2/dds/pose_conversion.hpp"
#include "litamin2/dds/time_conversion.hpp"

#include <cmath>

namespace litamin2::dds {

namespace {

/// J mapping the left update (phi, tau) to (dt, dphi) of the ROS order (see the header).
Matrix6d left_to_ros_jacobian(const Eigen::Isometry3d& pose) {
  Matrix6d j = Matrix6d::Zero();
  j.block<3, 3>(0, 0) = -skew(pose.translation());
  j.block<3, 3>(0, 3) = Eigen::Matrix3d::Identity();
  j.block<3, 3>(3, 0) = Eigen::Matrix3d::Identity();
  return j;
}

/// Inverse of left_to_ros_jacobian: (dt, dphi) -> (phi = dphi, tau = dt + [t]x dphi).
Matrix6d ros_to_left_jacobian(const Eigen::Isometry3d& pose) {
  Matrix6d j = Matrix6d::Zero();
  j.block<3, 3>(0, 3) = Eigen::Matrix3d::Identity();
  j.block<3, 3>(3, 0) = Eigen::Matrix3d::Identity();
  j.block<3, 3>(3, 3) = skew(pose.translation());
  return j;
}

std::array<double, 36> to_row_major(const Matrix6d& m) {
  std::array<double, 36> out{};
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) out[static_cast<std::size_t>(6 * r + c)] = m(r, c);
  }
  return out;
}

}  // namespace

Matrix6d ros_covariance_matrix(const std::array<double, 36>& a) {
  Matrix6d m;
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) m(r, c) = a[static_cast<std::size_t>(6 * r + c)];
  }
  return m;
}

std::array<double, 36> ros_pose_covariance(const Matrix6d& left_covariance,
                                           const Eigen::Isometry3d& pose) {
  const Matrix6d j = left_to_ros_jacobian(pose);
  Matrix6d ros = j * left_covariance * j.transpose();
  ros = 0.5 * (ros + ros.transpose()).eval();
  return to_row_major(ros);
}

Matrix6d left_covariance_from_ros(const std::array<double, 36>& ros_covariance,
                                  const Eigen::Isometry3d& pose) {
  const Matrix6d j = ros_to_left_jacobian(pose);
  Matrix6d left = j * ros_covariance_matrix(ros_covariance) * j.transpose();
  return 0.5 * (left + left.transpose());
}

std::array<double, 36> ros_twist_covariance(const Matrix6d& angular_linear_covariance) {
  Matrix6d p = Matrix6d::Zero();  // (angular, linear) -> (linear, angular)
  p.block<3, 3>(0, 3) = Eigen::Matrix3d::Identity();
  p.block<3, 3>(3, 0) = Eigen::Matrix3d::Identity();
  return to_row_major(p * angular_linear_covariance * p.transpose());
}

nav_msgs::msg::Odometry to_odometry(const Eigen::Isometry3d& pose, const Matrix6d& left_covariance,
                                    Stamp stamp, const std::string& frame_id,
                                    const std::string& child_frame_id,
                                    const std::optional<TwistEstimate>& twist) {
  nav_msgs::msg::Odometry msg;
  msg.header().stamp(to_time(stamp));
  msg.header().frame_id(frame_id);
  msg.child_frame_id(child_frame_id);
  msg.pose().pose(to_pose_msg(pose));
  msg.pose().covariance(ros_pose_covariance(left_covariance, pose));
  if (twist) {
    auto& t = msg.twist().twist();
    t.linear().x(twist->twist.linear.x());
    t.linear().y(twist->twist.linear.y());
    t.linear().z(twist->twist.linear.z());
    t.angular().x(twist->twist.angular.x());
    t.angular().y(twist->twist.angular.y());
    t.angular().z(twist->twist.angular.z());
    msg.twist().covariance(ros_twist_covariance(twist->covariance));
    return msg;
  }
  std::array<double, 36> twist_cov{};
  for (std::size_t i = 0; i < 6; ++i) twist_cov[7 * i] = -1.0;
  msg.twist().covariance(twist_cov);
  return msg;
}

const char* to_string(OdometryError error) {
  switch (error) {
    case OdometryError::kNone:
      return "none";
    case OdometryError::kBadPose:
      return "bad_pose";
    case OdometryError::kBadCovariance:
      return "bad_covariance";
    case OdometryError::kBadStamp:
      return "bad_stamp";
    case OdometryError::kBadTwist:
      return "bad_twist";
  }
  return "unknown";
}

OdometryConversion from_odometry(const nav_msgs::msg::Odometry& msg) {
  OdometryConversion out;
  const auto reject = [&](OdometryError error, std::string message) {
    out.error = error;
    out.message = std::move(message);
    return out;
  };
  const geometry_msgs::msg::Pose& p = msg.pose().pose();
  if (const auto why = pose_msg_error(p)) return reject(OdometryError::kBadPose, "pose: " + *why);
  if (const auto why = checks::covariance_error<6>(ros_covariance_matrix(msg.pose().covariance())))
    return reject(OdometryError::kBadCovariance, "pose covariance " + *why);
  if (msg.header().stamp().nanosec() >= 1'000'000'000u)
    return reject(OdometryError::kBadStamp,
                  "stamp nanosec " + std::to_string(msg.header().stamp().nanosec()) + " >= 1e9");
  const auto& twist = msg.twist().twist();
  const double t[] = {twist.linear().x(),  twist.linear().y(),  twist.linear().z(),
                      twist.angular().x(), twist.angular().y(), twist.angular().z()};
  for (double x : t)
    if (!std::isfinite(x)) return reject(OdometryError::kBadTwist, "non-finite twist");
  for (double x : msg.twist().covariance())
    if (!std::isfinite(x)) return reject(OdometryError::kBadTwist, "non-finite twist covariance");
  OdometrySample& sample = out.sample;
  sample.stamp = to_stamp(msg.header().stamp());
  sample.frame_id = msg.header().frame_id();
  sample.child_frame_id = msg.child_frame_id();
  sample.pose = from_pose_msg(p);
  sample.ros_covariance = ros_covariance_matrix(msg.pose().covariance());
  sample.left_covariance = left_covariance_from_ros(msg.pose().covariance(), sample.pose);
  return out;
}

}  // namespace litamin2::dds

#include "litamin2/dds/pose_conversion.hpp"

#include "litamin2/core/value_checks.hpp"

#include <cmath>

namespace litamin2::dds {

geometry_msgs::msg::Pose to_pose_msg(const Eigen::Isometry3d& pose) {
  geometry_msgs::msg::Pose msg;
  const Eigen::Vector3d t = pose.translation();
  msg.position().x(t.x());
  msg.position().y(t.y());
  msg.position().z(t.z());
  Eigen::Quaterniond q(pose.linear());
  q.normalize();
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();
  msg.orientation().x(q.x());
  msg.orientation().y(q.y());
  msg.orientation().z(q.z());
  msg.orientation().w(q.w());
  return msg;
}

std::optional<std::string> pose_msg_error(const geometry_msgs::msg::Pose& msg) {
  const auto& p = msg.position();
  if (auto why = checks::position_error(Eigen::Vector3d(p.x(), p.y(), p.z())))
    return "position " + *why;
  const auto& q = msg.orientation();
  if (auto why = checks::unit_quaternion_error(q.w(), q.x(), q.y(), q.z()))
    return "orientation " + *why;
  return std::nullopt;
}

Eigen::Isometry3d from_pose_msg(const geometry_msgs::msg::Pose& msg) {
  Eigen::Quaterniond q(msg.orientation().w(), msg.orientation().x(), msg.orientation().y(),
                       msg.orientation().z());
  const double norm = q.norm();
  if (norm > 0.0 && std::isfinite(norm)) q.coeffs() /= norm;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = q.toRotationMatrix();
  pose.translation() = Eigen::Vector3d(msg.position().x(), msg.position().y(), msg.position().z());
  return pose;
}

}  // namespace litamin2::dds

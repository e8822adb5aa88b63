#pragma once
/// Eigen::Isometry3d <-> geometry_msgs/Pose.

#include <Eigen/Geometry>

#include <optional>
#include <string>

#include "geometry_msgs/msg/Pose.h"

namespace litamin2::dds {

/// Position and unit quaternion (w >= 0) of a pose.
geometry_msgs::msg::Pose to_pose_msg(const Eigen::Isometry3d& pose);

/// Why a received pose is not a pose (std::nullopt when it is): a position that is not finite or
/// beyond checks::kMaxPosition, a quaternion that is not finite or whose norm is not 1 within
/// checks::kOrthonormalTolerance (a zero or unnormalised quaternion is rejected, not repaired).
std::optional<std::string> pose_msg_error(const geometry_msgs::msg::Pose& msg);

/// The pose of a message that passed pose_msg_error; the quaternion is divided by its norm (which
/// only removes the rounding of a unit quaternion).
Eigen::Isometry3d from_pose_msg(const geometry_msgs::msg::Pose& msg);

}  // namespace litamin2::dds

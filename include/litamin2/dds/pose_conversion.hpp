#pragma once
/// Eigen::Isometry3d <-> geometry_msgs/Pose.

#include <Eigen/Geometry>

#include "geometry_msgs/msg/Pose.h"

namespace litamin2::dds {

/// Position and unit quaternion (w >= 0) of a pose.
geometry_msgs::msg::Pose to_pose_msg(const Eigen::Isometry3d& pose);
/// The pose of a message; the quaternion is normalised (a zero quaternion gives identity).
Eigen::Isometry3d from_pose_msg(const geometry_msgs::msg::Pose& msg);

}  // namespace litamin2::dds

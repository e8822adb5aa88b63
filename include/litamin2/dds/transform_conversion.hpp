#pragma once
/// Eigen::Isometry3d -> geometry_msgs/TransformStamped and tf2_msgs/TFMessage (rt/tf,
/// rt/tf_static), and back for tests and readers.

#include "litamin2/core/stamp.hpp"

#include <Eigen/Geometry>

#include <string>

#include "geometry_msgs/msg/TransformStamped.h"
#include "tf2_msgs/msg/TFMessage.h"

namespace litamin2::dds {

/// The transform that places `child_frame` in `parent_frame`: `child_in_parent` maps child
/// coordinates to parent coordinates (as a pose of the child in the parent, the tf2
/// convention); unit quaternion with w >= 0, as to_pose_msg.
geometry_msgs::msg::TransformStamped to_transform_stamped(const Eigen::Isometry3d& child_in_parent,
                                                          Stamp stamp,
                                                          const std::string& parent_frame,
                                                          const std::string& child_frame);

/// The isometry of a transform (the quaternion normalised; callers check it first when it
/// comes from the network).
Eigen::Isometry3d from_transform_msg(const geometry_msgs::msg::Transform& msg);

/// A TFMessage holding the one transform.
tf2_msgs::msg::TFMessage to_tf_message(geometry_msgs::msg::TransformStamped transform);

}  // namespace litamin2::dds

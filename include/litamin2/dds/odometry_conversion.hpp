#pragma once
/// Tracker pose + covariance <-> nav_msgs/Odometry.
///
/// Covariance convention. The tracker (FrameResult::covariance) gives a 6x6 covariance of the
/// left update xi = (phi, tau): T <- (exp([phi]x), tau) * T, i.e. a rotation phi about the
/// world (odometry frame) origin followed by a translation tau, rotation block first. ROS's
/// PoseWithCovariance::covariance is row-major 6x6 over (x, y, z, rotation about X, Y, Z), the
/// position and fixed-axis rotation of the child frame in the header frame, translation first.
/// To first order the left update moves the position t by dt = tau + phi x t = tau - [t]x phi
/// and the orientation by the world-frame rotation phi, so with J = [[-[t]x, I], [I, 0]]
/// (mapping (phi, tau) to (dt, dphi)) the ROS covariance is J * C * J^T: the blocks are swapped
/// (translation first) and the rotation uncertainty's lever arm about the origin is added to
/// the position part. At t = 0 this is exactly the block reordering.

#include "litamin2/core/frame_twist.hpp"
#include "litamin2/core/so3.hpp"
#include "litamin2/core/stamp.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <optional>
#include <string>

#include "nav_msgs/msg/Odometry.h"

namespace litamin2::dds {

/// ROS pose covariance (row-major, (x, y, z, rx, ry, rz)) of a pose whose covariance is
/// `left_covariance` in the tracker's (phi, tau) left-update coordinates (see above).
std::array<double, 36> ros_pose_covariance(const Matrix6d& left_covariance,
                                           const Eigen::Isometry3d& pose);
/// The 6x6 matrix of a row-major ROS covariance array.
Matrix6d ros_covariance_matrix(const std::array<double, 36>& ros_covariance);
/// Inverse of ros_pose_covariance.
Matrix6d left_covariance_from_ros(const std::array<double, 36>& ros_covariance,
                                  const Eigen::Isometry3d& pose);

/// ROS twist covariance (row-major over (vx, vy, vz, wx, wy, wz), linear first) of a
/// covariance over (angular, linear) (TwistEstimate::covariance): the blocks swapped.
std::array<double, 36> ros_twist_covariance(const Matrix6d& angular_linear_covariance);

/// Builds an Odometry message: header (stamp, frame_id), child_frame_id, pose, pose
/// covariance converted by ros_pose_covariance; the twist (in the child frame, as ROS defines
/// it) and its covariance (ros_twist_covariance) from `twist`, or, without one, zero with
/// covariance diagonal -1 (ROS's "unknown").
nav_msgs::msg::Odometry to_odometry(const Eigen::Isometry3d& pose, const Matrix6d& left_covariance,
                                    Stamp stamp, const std::string& frame_id,
                                    const std::string& child_frame_id,
                                    const std::optional<TwistEstimate>& twist = std::nullopt);

/// The content of an Odometry message, as the tracker's types.
struct OdometrySample {
  Stamp stamp;
  std::string frame_id;
  std::string child_frame_id;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  /// Covariance converted back to (phi, tau) left-update coordinates.
  Matrix6d left_covariance = Matrix6d::Zero();
  /// The message's covariance as a matrix (row-major in the message), ROS order.
  Matrix6d ros_covariance = Matrix6d::Zero();
};

/// Why an Odometry message was rejected.
enum class OdometryError {
  kNone = 0,
  /// The pose is not a pose (pose_msg_error: non-finite or out-of-bounds position, quaternion
  /// not of norm 1).
  kBadPose,
  /// The pose covariance is not finite, bounded, symmetric and positive semi-definite
  /// (checks::covariance_error).
  kBadCovariance,
  /// header.stamp.nanosec >= 1e9.
  kBadStamp,
  /// The twist or its covariance has a NaN or +-Inf (ROS's -1 for "unknown" is accepted).
  kBadTwist,
};

/// Short name of an error ("bad_pose", ...), for counters and logs.
const char* to_string(OdometryError error);

/// Result of from_odometry (the shape of CloudConversion and PatchConversion).
struct OdometryConversion {
  OdometryError error = OdometryError::kNone;
  /// Human-readable reason when error != kNone.
  std::string message;
  /// The message's content (unspecified when rejected).
  OdometrySample sample;
  bool ok() const { return error == OdometryError::kNone; }
};

/// Reads and checks an Odometry message (docs/security.md, "Validation"). Never throws for bad
/// input.
OdometryConversion from_odometry(const nav_msgs::msg::Odometry& msg);

}  // namespace litamin2::dds

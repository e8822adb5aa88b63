#pragma once
/// Rotation angle of the relative rotation between two rotation matrices.

#include <Eigen/Core>

namespace litamin2::eval {

/// Angle in radians, in [0, pi], of the rotation a^T * b (the rotation taking a to b).
/// Computed as atan2(|axis part|, (trace - 1) / 2) with cos clamped to [-1, 1] like the KITTI
/// devkit's acos(max(min(0.5 * (trace - 1), 1), -1)). Same value for proper rotations, but
/// accurate near 0 (acos loses half of the digits there) and exactly 0 when a == b.
double rotation_angle_between(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b);

/// Angle in radians, in [0, pi], of rotation matrix r (rotation_angle_between(I, r)).
double rotation_angle(const Eigen::Matrix3d& r);

}  // namespace litamin2::eval

#pragma once
/// Error between the estimated and the true relative motion of a pair of frames.

#include <Eigen/Geometry>

namespace litamin2::eval {

/// Translation and rotation magnitude of a relative pose error.
struct RelativeError {
  /// Norm of the translation of the error, in metres.
  double translation = 0.0;
  /// Rotation angle of the error, in radians.
  double rotation = 0.0;
};

/// Relative motion inv(from) * to, treating both poses as rigid (inverse rotation = transpose).
Eigen::Isometry3d relative_motion(const Eigen::Isometry3d& from, const Eigen::Isometry3d& to);

/// Error inv(delta_est) * delta_gt with delta = inv(P_first) * P_last, as in the KITTI devkit.
/// Exactly zero when the estimated poses equal the ground-truth poses.
RelativeError relative_error(const Eigen::Isometry3d& gt_first, const Eigen::Isometry3d& gt_last,
                             const Eigen::Isometry3d& est_first, const Eigen::Isometry3d& est_last);

}  // namespace litamin2::eval

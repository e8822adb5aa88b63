#pragma once
/// One normal distribution of points: what a LiTAMIN2 voxel is reduced to.

#include <Eigen/Core>

namespace litamin2 {

struct Distribution {
  /// Mean of the voxel's points (metres, in the frame the points were given in).
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  /// Covariance of the points, lightly regularised: the ICP term's C_qp (Eq. 3) uses it.
  Eigen::Matrix3d cov = Eigen::Matrix3d::Identity();
  /// Covariance regularised more strongly for the Cov term (Eq. 4), which compares shapes
  /// through inverses and so amplifies the noise of a flat voxel's thin axis.
  Eigen::Matrix3d shape_cov = Eigen::Matrix3d::Identity();
  /// Inverse of `shape_cov`.
  Eigen::Matrix3d shape_cov_inv = Eigen::Matrix3d::Identity();
  /// Number of points the distribution was estimated from.
  int count = 0;
};

}  // namespace litamin2

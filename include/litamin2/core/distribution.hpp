#pragma once
/// One normal distribution of points: what a LiTAMIN2 voxel is reduced to.

#include <Eigen/Core>

namespace litamin2 {

struct Distribution {
  /// Mean of the voxel's points (metres, in the frame the points were given in).
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  /// Regularised covariance of the points (see CovarianceRegularizer).
  Eigen::Matrix3d cov = Eigen::Matrix3d::Identity();
  /// Inverse of `cov`, computed once from its eigen-decomposition.
  Eigen::Matrix3d cov_inv = Eigen::Matrix3d::Identity();
  /// Number of points the distribution was estimated from.
  int count = 0;
};

}  // namespace litamin2

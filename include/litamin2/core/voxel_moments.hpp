#pragma once
/// Running first and second moments of the points of one voxel.
///
/// Sums are kept in double and relative to a local origin (the voxel's centre), so a voxel at
/// 80 m keeps its covariance: float sums of x^2 at that range lose it.

#include "litamin2/core/covariance_regularizer.hpp"
#include "litamin2/core/distribution.hpp"

#include <Eigen/Core>

namespace litamin2 {

struct VoxelMoments {
  /// Local origin the sums are relative to.
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  /// Number of points.
  int count = 0;
  /// Sum of (p - origin).
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  /// Upper triangle of the sum of (p - origin)(p - origin)^T: xx, xy, xz, yy, yz, zz.
  Eigen::Matrix<double, 6, 1> sum_sq = Eigen::Matrix<double, 6, 1>::Zero();

  /// Adds one point.
  void add(const Eigen::Vector3d& p) {
    const Eigen::Vector3d d = p - origin;
    ++count;
    sum += d;
    sum_sq(0) += d.x() * d.x();
    sum_sq(1) += d.x() * d.y();
    sum_sq(2) += d.x() * d.z();
    sum_sq(3) += d.y() * d.y();
    sum_sq(4) += d.y() * d.z();
    sum_sq(5) += d.z() * d.z();
  }

  /// Adds the moments of another voxel with the same origin.
  void merge(const VoxelMoments& other) {
    count += other.count;
    sum += other.sum;
    sum_sq += other.sum_sq;
  }

  /// The moments of the same points moved by (R, t), relative to `new_origin`. With
  /// d = R origin + t - new_origin: sum' = R sum + n d,
  /// S' = R S R^T + R sum d^T + d (R sum)^T + n d d^T.
  VoxelMoments transformed(const Eigen::Matrix3d& r, const Eigen::Vector3d& t,
                           const Eigen::Vector3d& new_origin) const {
    VoxelMoments out;
    out.origin = new_origin;
    out.count = count;
    const double n = static_cast<double>(count);
    const Eigen::Vector3d d = r * origin + t - new_origin;
    const Eigen::Vector3d rs = r * sum;
    out.sum = rs + n * d;
    const Eigen::Matrix3d s = r * second_moment() * r.transpose() + rs * d.transpose() +
                              d * rs.transpose() + n * d * d.transpose();
    out.sum_sq << s(0, 0), s(0, 1), s(0, 2), s(1, 1), s(1, 2), s(2, 2);
    return out;
  }

  /// Moments of `dist.count` points with mean `mean` and maximum-likelihood covariance `cov`,
  /// relative to `origin` (to_distribution's inverse, before regularisation): with
  /// d = mean - origin, sum = n d, S = n (cov + d d^T).
  static VoxelMoments of_distribution(const Eigen::Vector3d& mean, const Eigen::Matrix3d& cov,
                                      int count, const Eigen::Vector3d& origin) {
    VoxelMoments out;
    out.origin = origin;
    out.count = count;
    const double n = static_cast<double>(count);
    const Eigen::Vector3d d = mean - origin;
    out.sum = n * d;
    const Eigen::Matrix3d s = n * (cov + d * d.transpose());
    out.sum_sq << s(0, 0), s(0, 1), s(0, 2), s(1, 1), s(1, 2), s(2, 2);
    return out;
  }

  /// The sum of (p - origin)(p - origin)^T as a matrix.
  Eigen::Matrix3d second_moment() const {
    Eigen::Matrix3d m;
    m << sum_sq(0), sum_sq(1), sum_sq(2), sum_sq(1), sum_sq(3), sum_sq(4), sum_sq(2), sum_sq(4),
        sum_sq(5);
    return m;
  }

  /// Mean and (maximum-likelihood) covariance, regularised; valid for count >= 1.
  Distribution to_distribution(const RegularizerConfig& regularizer) const {
    Distribution dist;
    const double n = static_cast<double>(count);
    const Eigen::Vector3d local_mean = sum / n;
    dist.mean = origin + local_mean;
    const Eigen::Matrix3d raw = second_moment() / n - local_mean * local_mean.transpose();
    dist.count = count;
    regularize_for_terms(regularizer, raw, dist.cov, dist.shape_cov, dist.shape_cov_inv);
    return dist;
  }
};

}  // namespace litamin2

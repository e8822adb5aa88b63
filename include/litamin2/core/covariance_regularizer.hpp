#pragma once
/// Regularised covariance and inverse for flat or linear voxels (walls, road, poles).
///
/// A voxel on a wall has one eigenvalue near zero, so its raw inverse is huge and the Cov term
/// (paper Eq. 4), which uses Cp^-1 and Cq^-1, is dominated by noise. Two remedies are offered:
/// - EigenClamp: eigenvalues below `min_eigen_ratio * lambda_max` are raised to that floor
///   (shape kept where it is well conditioned);
/// - Plane: GICP's plane model, eigenvalues replaced by (epsilon, 1, 1) * scale, with scale the
///   largest eigenvalue so the distribution keeps its size.
/// The default is chosen by measurement (docs/accuracy.md).

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

namespace litamin2 {

enum class RegularizationMethod { kEigenClamp, kPlane };

struct RegularizerConfig {
  /// Which remedy to apply.
  RegularizationMethod method = RegularizationMethod::kEigenClamp;
  /// EigenClamp: floor of each eigenvalue relative to the largest, for the ICP term.
  double min_eigen_ratio = 1e-4;
  /// EigenClamp: the same floor for the Cov term's shapes.
  double shape_min_eigen_ratio = 0.3;
  /// Plane: the small eigenvalue relative to the others (GICP uses 1e-3).
  double plane_epsilon = 1e-3;
  /// Absolute eigenvalue floor in m^2 for both methods (guards all-zero covariances).
  double min_eigenvalue = 1e-6;
};

/// Regularises `cov` in place (with min_eigen_ratio) and writes its inverse.
void regularize_covariance(const RegularizerConfig& config, Eigen::Matrix3d& cov,
                           Eigen::Matrix3d& cov_inv);

/// From a raw covariance, with one eigen-decomposition: the ICP term's covariance (clamped with
/// min_eigen_ratio) and the Cov term's shape and its inverse (clamped with
/// shape_min_eigen_ratio). With the Plane method both use plane_epsilon.
void regularize_for_terms(const RegularizerConfig& config, const Eigen::Matrix3d& raw,
                          Eigen::Matrix3d& cov, Eigen::Matrix3d& shape_cov,
                          Eigen::Matrix3d& shape_cov_inv);
/// The same from the raw covariance's closed-form eigen-decomposition (computeDirect, with
/// eigenvectors), when the caller has it already (the store's decoder checks the eigenvalues):
/// identical results.
void regularize_for_terms(const RegularizerConfig& config,
                          const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>& eigen_of_raw,
                          Eigen::Matrix3d& cov, Eigen::Matrix3d& shape_cov,
                          Eigen::Matrix3d& shape_cov_inv);

}  // namespace litamin2

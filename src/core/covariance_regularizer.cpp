#include "litamin2/core/covariance_regularizer.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>

namespace litamin2 {

namespace {

/// Regularised eigenvalues (ascending input) for the given clamp ratio.
Eigen::Vector3d regularized_values(const RegularizerConfig& config, const Eigen::Vector3d& values,
                                   double ratio) {
  const double largest = std::max(values(2), config.min_eigenvalue);
  if (config.method == RegularizationMethod::kPlane) {
    return Eigen::Vector3d(config.plane_epsilon, 1.0, 1.0) * largest;
  }
  return values.cwiseMax(std::max(ratio * largest, config.min_eigenvalue));
}

}  // namespace

void regularize_covariance(const RegularizerConfig& config, Eigen::Matrix3d& cov,
                           Eigen::Matrix3d& cov_inv) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(cov);
  const Eigen::Vector3d values =
      regularized_values(config, eig.eigenvalues(), config.min_eigen_ratio);
  const Eigen::Matrix3d& vectors = eig.eigenvectors();
  cov = vectors * values.asDiagonal() * vectors.transpose();
  cov_inv = vectors * values.cwiseInverse().asDiagonal() * vectors.transpose();
}

void regularize_for_terms(const RegularizerConfig& config, const Eigen::Matrix3d& raw,
                          Eigen::Matrix3d& cov, Eigen::Matrix3d& shape_cov,
                          Eigen::Matrix3d& shape_cov_inv) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(raw);
  regularize_for_terms(config, eig, cov, shape_cov, shape_cov_inv);
}

void regularize_for_terms(const RegularizerConfig& config,
                          const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>& eig,
                          Eigen::Matrix3d& cov, Eigen::Matrix3d& shape_cov,
                          Eigen::Matrix3d& shape_cov_inv) {
  const Eigen::Matrix3d& vectors = eig.eigenvectors();
  const Eigen::Vector3d icp = regularized_values(config, eig.eigenvalues(), config.min_eigen_ratio);
  const Eigen::Vector3d shape =
      regularized_values(config, eig.eigenvalues(), config.shape_min_eigen_ratio);
  cov = vectors * icp.asDiagonal() * vectors.transpose();
  shape_cov = vectors * shape.asDiagonal() * vectors.transpose();
  shape_cov_inv = vectors * shape.cwiseInverse().asDiagonal() * vectors.transpose();
}

}  // namespace litamin2

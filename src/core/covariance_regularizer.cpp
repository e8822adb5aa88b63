#include "litamin2/core/covariance_regularizer.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>

namespace litamin2 {

void regularize_covariance(const RegularizerConfig& config, Eigen::Matrix3d& cov,
                           Eigen::Matrix3d& cov_inv) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(cov);
  Eigen::Vector3d values = eig.eigenvalues();  // ascending
  const double largest = std::max(values(2), config.min_eigenvalue);
  if (config.method == RegularizationMethod::Plane) {
    values = Eigen::Vector3d(config.plane_epsilon, 1.0, 1.0) * largest;
  } else {
    const double floor = std::max(config.min_eigen_ratio * largest, config.min_eigenvalue);
    values = values.cwiseMax(floor);
  }
  const Eigen::Matrix3d& vectors = eig.eigenvectors();
  cov = vectors * values.asDiagonal() * vectors.transpose();
  cov_inv = vectors * values.cwiseInverse().asDiagonal() * vectors.transpose();
}

}  // namespace litamin2

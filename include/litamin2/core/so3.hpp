#pragma once
/// Small SO(3)/SE(3) helpers: skew matrices and the pose update used by the solver.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace litamin2 {

/// [v]x, the matrix with [v]x w = v x w.
inline Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

/// vee([a]x) = a for the antisymmetric part of m.
inline Eigen::Vector3d vee(const Eigen::Matrix3d& m) {
  return 0.5 * Eigen::Vector3d(m(2, 1) - m(1, 2), m(0, 2) - m(2, 0), m(1, 0) - m(0, 1));
}

/// exp([phi]x) by Rodrigues' formula.
inline Eigen::Matrix3d so3_exp(const Eigen::Vector3d& phi) {
  const double angle = phi.norm();
  if (angle < 1e-12) return Eigen::Matrix3d::Identity() + skew(phi);
  return Eigen::AngleAxisd(angle, phi / angle).toRotationMatrix();
}

/// The solver's update of a pose by xi = (phi, tau): R <- exp([phi]x) R, t <- exp([phi]x) t + tau,
/// i.e. left multiplication by (exp([phi]x), tau). A world point y = R p + t moves to
/// y + phi x y + tau to first order, so dy/dphi = -[y]x and dy/dtau = I.
inline Eigen::Isometry3d apply_left_update(const Eigen::Matrix<double, 6, 1>& xi,
                                           const Eigen::Isometry3d& pose) {
  Eigen::Isometry3d delta = Eigen::Isometry3d::Identity();
  delta.linear() = so3_exp(xi.head<3>());
  delta.translation() = xi.tail<3>();
  Eigen::Isometry3d updated = delta * pose;
  // Re-orthonormalise to keep rounding from accumulating over thousands of frames.
  const Eigen::Quaterniond q(updated.linear());
  updated.linear() = q.normalized().toRotationMatrix();
  return updated;
}

}  // namespace litamin2

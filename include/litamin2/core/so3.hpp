#pragma once
/// Small SO(3)/SE(3) helpers: skew matrices, the pose update used by the solver, and the
/// adjoint that moves a pose covariance between frames.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace litamin2 {

/// A pose increment or gradient, (phi, tau): rotation first (the solver's convention).
using Vector6d = Eigen::Matrix<double, 6, 1>;
/// A 6x6 block over (phi, tau): Hessians, information and covariance matrices of poses.
using Matrix6d = Eigen::Matrix<double, 6, 6>;

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
inline Eigen::Isometry3d apply_left_update(const Vector6d& xi, const Eigen::Isometry3d& pose) {
  Eigen::Isometry3d delta = Eigen::Isometry3d::Identity();
  delta.linear() = so3_exp(xi.head<3>());
  delta.translation() = xi.tail<3>();
  Eigen::Isometry3d updated = delta * pose;
  // Re-orthonormalise to keep rounding from accumulating over thousands of frames.
  const Eigen::Quaterniond q(updated.linear());
  updated.linear() = q.normalized().toRotationMatrix();
  return updated;
}

/// The pose with its rotation projected back onto SO(3) (through the nearest unit
/// quaternion): products of poses drift off orthonormal by rounding, and a correction made
/// from a pose and applied to it doubles that drift (T' = S T^-1 T with T^-1 taken as R^T),
/// so a pose corrected again and again must be re-orthonormalised.
inline Eigen::Isometry3d orthonormalized(const Eigen::Isometry3d& pose) {
  Eigen::Isometry3d out = pose;
  out.linear() = Eigen::Quaterniond(pose.linear()).normalized().toRotationMatrix();
  return out;
}

/// The adjoint of E = (R, t) in the left-update coordinates xi = (phi, tau):
/// E exp(xi) T E^-1 = exp(Ad_E xi) (E T E^-1), with Ad_E = [[R, 0], [[t]x R, R]].
inline Matrix6d adjoint(const Eigen::Isometry3d& pose) {
  const Eigen::Matrix3d r = pose.linear();
  Matrix6d ad = Matrix6d::Zero();
  ad.topLeftCorner<3, 3>() = r;
  ad.bottomLeftCorner<3, 3>() = skew(pose.translation()) * r;
  ad.bottomRightCorner<3, 3>() = r;
  return ad;
}

/// The left-update covariance of E T E^-1 (or of E T: the same map) when T's is `covariance`:
/// Ad_E C Ad_E^T. Moves a sensor pose's covariance to the vehicle base by the sensor's
/// extrinsic, or an odometry covariance to the map frame by a correction.
inline Matrix6d transform_left_covariance(const Matrix6d& covariance,
                                          const Eigen::Isometry3d& pose) {
  const Matrix6d ad = adjoint(pose);
  return ad * covariance * ad.transpose();
}

}  // namespace litamin2

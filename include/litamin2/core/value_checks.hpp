#pragma once
/// Checks of values that come from outside (the network, files, the store) before they become
/// the method's types: finite, bounded, rotations orthonormal, covariances symmetric positive
/// semi-definite. Each returns std::nullopt when the value is acceptable, else why not (a short
/// phrase for a message: "is not symmetric", ...). Invalid values are rejected, never repaired.
/// Header-only: io, store and dds use it (docs/security.md, "Validation").

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <cmath>
#include <optional>
#include <sstream>
#include <string>

namespace litamin2::checks {

/// Largest |coordinate| of a position, metres: 10'000 km holds any map frame on Earth
/// (even ECEF or UTM coordinates) and keeps products of positions and covariances (the lever
/// arms of odometry_conversion.hpp) far from overflow.
constexpr double kMaxPosition = 1e7;
/// Largest |entry| of a covariance or information matrix.
constexpr double kMaxCovarianceEntry = 1e12;
/// Rotations: max |(R^T R - I)_ij|; unit quaternions: | |q| - 1 |. KITTI's 7-digit text poses
/// are within 3e-7, float quaternions within 1e-7; garbage is far beyond.
constexpr double kOrthonormalTolerance = 1e-3;
/// Symmetric within this fraction of the largest |entry|; positive semi-definite when the
/// smallest eigenvalue is >= -this fraction of the largest |eigenvalue| (rounding).
constexpr double kMatrixTolerance = 1e-6;

/// The text of a number for messages ("1e+300").
inline std::string number_text(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

/// Every entry is finite and |entry| <= bound.
template <class Derived>
std::optional<std::string> bounded_error(const Eigen::MatrixBase<Derived>& m, double bound) {
  for (Eigen::Index i = 0; i < m.size(); ++i) {
    const double v = static_cast<double>(m.derived().data()[i]);
    if (!std::isfinite(v)) return "holds a non-finite value (" + number_text(v) + ")";
    if (std::fabs(v) > bound) return "holds " + number_text(v) + ", beyond +-" + number_text(bound);
  }
  return std::nullopt;
}

/// A position: finite, every coordinate within +-kMaxPosition.
inline std::optional<std::string> position_error(const Eigen::Vector3d& t) {
  return bounded_error(t, kMaxPosition);
}

/// A rotation matrix: finite, orthonormal within kOrthonormalTolerance, determinant +1 (a
/// reflection is not a rotation).
inline std::optional<std::string> rotation_error(const Eigen::Matrix3d& r) {
  if (!r.allFinite()) return std::string("holds a non-finite value");
  const double off = (r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (!(off <= kOrthonormalTolerance))
    return "is not orthonormal (max |R^T R - I| = " + number_text(off) + ")";
  if (!(r.determinant() > 0.0)) return "is a reflection (determinant -1), not a rotation";
  return std::nullopt;
}

/// A unit quaternion (any order of components): finite, norm 1 within kOrthonormalTolerance.
inline std::optional<std::string> unit_quaternion_error(double w, double x, double y, double z) {
  const double norm = std::sqrt(w * w + x * x + y * y + z * z);
  if (!std::isfinite(norm)) return std::string("holds a non-finite value");
  if (!(std::fabs(norm - 1.0) <= kOrthonormalTolerance))
    return "is not a unit quaternion (norm " + number_text(norm) + ")";
  return std::nullopt;
}

/// A covariance or information matrix: finite, |entries| <= kMaxCovarianceEntry, symmetric and
/// positive semi-definite within kMatrixTolerance.
template <int N>
std::optional<std::string> covariance_error(const Eigen::Matrix<double, N, N>& c) {
  if (auto why = bounded_error(c, kMaxCovarianceEntry)) return why;
  const double scale = c.cwiseAbs().maxCoeff();
  if (scale == 0.0) return std::nullopt;
  const double asymmetry = (c - c.transpose()).cwiseAbs().maxCoeff();
  if (asymmetry > kMatrixTolerance * scale)
    return "is not symmetric (max |C - C^T| = " + number_text(asymmetry) + ")";
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> solver(c,
                                                                          Eigen::EigenvaluesOnly);
  if (solver.info() != Eigen::Success) return std::string("has no eigen-decomposition");
  const auto& eigen = solver.eigenvalues();
  const double largest = eigen.cwiseAbs().maxCoeff();
  if (eigen.minCoeff() < -kMatrixTolerance * largest)
    return "is not positive semi-definite (smallest eigenvalue " + number_text(eigen.minCoeff()) +
           ")";
  return std::nullopt;
}

}  // namespace litamin2::checks

#pragma once
/// The ICP term of LiTAMIN2 (paper Eq. 3) for one correspondence, with derivatives with
/// respect to the left pose update xi = (phi, tau) (see so3.hpp).
///
///   E_icp = r^T C_qp r,   r = q - (R p + t),
///   C_qp  = (Cq + R Cp R^T + lambda I)^-1 / ||(Cq + R Cp R^T + lambda I)^-1||_F.
///
/// C_qp is held fixed within one Newton iteration (as GICP does), so with J = dr/dxi =
/// [ [y]x  -I ] (y = R p + t) the gradient is 2 J^T C r and the Hessian 2 J^T C J.

#include "litamin2/core/so3.hpp"

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

namespace litamin2 {

/// The normalised combined precision C_qp of Eq. 3. `rotated_cp` is R Cp R^T.
inline Eigen::Matrix3d combined_precision(const Eigen::Matrix3d& cq,
                                          const Eigen::Matrix3d& rotated_cp, double lambda) {
  const Eigen::Matrix3d combined = cq + rotated_cp + lambda * Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d inverse = combined.inverse();
  return inverse / inverse.norm();
}

/// Smallest over largest eigenvalue of the combined covariance Cq + R Cp R^T + lambda I of
/// Eq. 3: near 0 for a plane or a line, near 1 for a round distribution.
inline double combined_isotropy(const Eigen::Matrix3d& cq, const Eigen::Matrix3d& rotated_cp,
                                double lambda) {
  const Eigen::Matrix3d combined = cq + rotated_cp + lambda * Eigen::Matrix3d::Identity();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(combined, Eigen::EigenvaluesOnly);
  return eig.eigenvalues()(0) / eig.eigenvalues()(2);
}

/// Middle over largest eigenvalue of the combined covariance Cq + R Cp R^T + lambda I of Eq. 3:
/// near 0 only for a line (both distributions line-like and parallel), near 1 for a plane or a
/// round distribution.
inline double combined_spread(const Eigen::Matrix3d& cq, const Eigen::Matrix3d& rotated_cp,
                              double lambda) {
  const Eigen::Matrix3d combined = cq + rotated_cp + lambda * Eigen::Matrix3d::Identity();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(combined, Eigen::EigenvaluesOnly);
  return eig.eigenvalues()(1) / eig.eigenvalues()(2);
}

/// combined_isotropy(cq, rotated_cp, lambda) > max_isotropy, from the trace and determinant
/// where they settle it (most distributions are clearly flat), else from the eigenvalues.
/// With eigenvalues a <= b <= c of the combined covariance (trace s, determinant d):
///   a^3 <= abc = d and c >= s/3, so (a/c)^3 <= 27 d / s^3;
///   a/c = d / (b c^2) and b c^2 <= 4 s^3 / 27 (b + c <= s, b <= c), so a/c >= 27 d / (4 s^3).
inline bool combined_is_round(const Eigen::Matrix3d& cq, const Eigen::Matrix3d& rotated_cp,
                              double lambda, double max_isotropy) {
  const Eigen::Matrix3d combined = cq + rotated_cp + lambda * Eigen::Matrix3d::Identity();
  const double s = combined.trace();
  const double d = combined.determinant();
  const double ratio = 27.0 * d / (s * s * s);  // (a/c)^3 <= ratio <= 4 a/c
  // Margins keep rounding in the bounds from deciding a case the eigenvalues would not.
  if (ratio < max_isotropy * max_isotropy * max_isotropy * (1.0 - 1e-9)) return false;
  if (ratio > 4.0 * max_isotropy * (1.0 + 1e-9)) return true;
  return combined_isotropy(cq, rotated_cp, lambda) > max_isotropy;
}

/// combined_spread(cq, rotated_cp, lambda) < line_gate, from the trace, the sum of principal
/// 2x2 minors and the Frobenius norm where they settle it (most distributions are clearly
/// planes or clearly lines), else from the eigenvalues. With eigenvalues 0 < a <= b <= c of the
/// combined covariance, s = a + b + c, p = ab + ac + bc and q = a^2 + b^2 + c^2 (= ||.||_F^2):
///   c >= q / s (q <= c s) and b c <= p, so b / c <= p / c^2 <= p s^2 / q^2;
///   p <= b^2 + 2 b c (a <= b) and c^2 <= q, so b / c >= sqrt(1 + p / c^2) - 1
///   >= sqrt(1 + p / q) - 1, which is >= g when p / q >= 2 g + g^2.
inline bool combined_is_line(const Eigen::Matrix3d& cq, const Eigen::Matrix3d& rotated_cp,
                             double lambda, double line_gate) {
  const Eigen::Matrix3d m = cq + rotated_cp + lambda * Eigen::Matrix3d::Identity();
  const double s = m.trace();
  const double p = m(0, 0) * m(1, 1) - m(0, 1) * m(1, 0) + m(0, 0) * m(2, 2) - m(0, 2) * m(2, 0) +
                   m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1);
  const double q = m.squaredNorm();
  // Margins keep rounding in the bounds from deciding a case the eigenvalues would not.
  if (p * s * s < line_gate * q * q * (1.0 - 1e-9)) return true;
  if (p > (2.0 * line_gate + line_gate * line_gate) * q * (1.0 + 1e-9)) return false;
  return combined_spread(cq, rotated_cp, lambda) < line_gate;
}

/// Keeps only the normal of a plane-like combined precision C_qp (Eq. 3), for
/// RegistrationConfig::normal_only_ratio: where its two weaker eigenvalues together are below
/// `ratio` times the strongest, C_qp is replaced by s n n^T (n the strongest direction, s its
/// eigenvalue) and true is returned; otherwise it is left as it is. n comes from three power
/// iterations from the column with the largest diagonal (for a plane-like C_qp the normal's
/// component along that axis is about 1/sqrt(3) or more), so its error is of order
/// (second / strongest eigenvalue)^3; s is the Rayleigh quotient n^T C_qp n. A line (two
/// strong directions) is left whole. With `normal`, n is written there when true is returned.
inline bool keep_normal_only(Eigen::Matrix3d& precision, double ratio,
                             Eigen::Vector3d* normal = nullptr) {
  int column = 0;
  precision.diagonal().maxCoeff(&column);
  Eigen::Vector3d n = precision * precision.col(column);
  n = precision * n;
  const double length = n.norm();
  if (!(length > 0.0)) return false;
  n /= length;
  const double strongest = n.dot(precision * n);
  if (precision.trace() - strongest >= ratio * strongest) return false;
  precision = strongest * n * n.transpose();
  if (normal) *normal = n;
  return true;
}

/// The weight tau^2 / (tau^2 + t^2) of a plane of thickness t (standard deviation along its
/// normal) in the normal-only refinement (RegistrationConfig::normal_only_thickness): about 1
/// for a plane much thinner than tau, 1/2 at tau, falling as 1/t^2 beyond. tau 0: always 1.
inline double plane_thickness_weight(double thickness_sq, double tau) {
  if (!(tau > 0.0)) return 1.0;
  return tau * tau / (tau * tau + thickness_sq);
}

struct IcpTerm {
  /// E_icp.
  double energy = 0.0;
  /// dE/dxi.
  Eigen::Matrix<double, 6, 1> gradient;
  /// Gauss-Newton Hessian 2 J^T C J.
  Matrix6d hessian;
};

/// dE/dxi = 2 J^T C r of the term with precision C, for y = R p + t and r = q - y.
inline Eigen::Matrix<double, 6, 1> icp_gradient(const Eigen::Vector3d& y, const Eigen::Vector3d& r,
                                                const Eigen::Matrix3d& precision) {
  const Eigen::Vector3d cr = precision * r;
  // J = [ [y]x  -I ];  J^T v = ( [y]x^T v ; -v ) = ( -y x v ; -v ) = ( v x y ; -v ).
  Eigen::Matrix<double, 6, 1> gradient;
  gradient.head<3>() = 2.0 * cr.cross(y);
  gradient.tail<3>() = -2.0 * cr;
  return gradient;
}

/// P = 2 J^T C = ( 2 [y]x^T C ; -2 C ) for J = [ [y]x  -I ], written out: the left factor of
/// icp_hessian and add_icp_hessian_lower.
inline Eigen::Matrix<double, 6, 3> icp_hessian_factor(const Eigen::Vector3d& y,
                                                      const Eigen::Matrix3d& precision) {
  const Eigen::Vector3d t = 2.0 * y;
  Eigen::Matrix<double, 6, 3> p;
  for (int b = 0; b < 3; ++b) {
    // Rows of [y]x^T: (0, z, -y), (-z, 0, x), (y, -x, 0).
    p(0, b) = t.z() * precision(1, b) - t.y() * precision(2, b);
    p(1, b) = t.x() * precision(2, b) - t.z() * precision(0, b);
    p(2, b) = t.y() * precision(0, b) - t.x() * precision(1, b);
    p.block<3, 1>(3, b) = -2.0 * precision.col(b);
  }
  return p;
}

/// The Gauss-Newton Hessian 2 J^T C J of the term with precision C, for y = R p + t, with
/// J = [ [y]x  -I ] written out: with P = icp_hessian_factor, 2 J^T C J is ( P [y]x , -P ).
/// Each entry is a sum of two products (the zeros of [y]x and I left out) or a negation, so it
/// equals the dense product's bit for bit (adding a zero product is exact and a sum of two
/// terms is the same in either order; scaling by 2 is exact); it costs about a third of the
/// dense product's operations.
inline Matrix6d icp_hessian(const Eigen::Vector3d& y, const Eigen::Matrix3d& precision) {
  const Eigen::Matrix<double, 6, 3> p = icp_hessian_factor(y, precision);
  Matrix6d hessian;
  // Columns of [y]x: (0, z, -y), (-z, 0, x), (y, -x, 0).
  hessian.col(0) = p.col(1) * y.z() - p.col(2) * y.y();
  hessian.col(1) = p.col(2) * y.x() - p.col(0) * y.z();
  hessian.col(2) = p.col(0) * y.y() - p.col(1) * y.x();
  hessian.rightCols<3>() = -p;
  return hessian;
}

/// sum += weight * icp_hessian(y, precision) on the lower triangle (row >= column) only; the
/// strictly upper triangle is left as it is. Each entry is computed as icp_hessian computes it,
/// so bit for bit the same as adding weight times icp_hessian's entry. An LDLT or LLT reads
/// only this triangle (Eigen's default): a sum of these, mirrored once, is the full sum for 21
/// of the 36 entries' work.
inline void add_icp_hessian_lower(Matrix6d& sum, const Eigen::Vector3d& y,
                                  const Eigen::Matrix3d& precision, double weight) {
  const Eigen::Matrix<double, 6, 3> p = icp_hessian_factor(y, precision);
  // icp_hessian's columns, from the diagonal down.
  sum.col(0) += weight * (p.col(1) * y.z() - p.col(2) * y.y());
  sum.block<5, 1>(1, 1) += weight * (p.block<5, 1>(1, 2) * y.x() - p.block<5, 1>(1, 0) * y.z());
  sum.block<4, 1>(2, 2) += weight * (p.block<4, 1>(2, 0) * y.y() - p.block<4, 1>(2, 1) * y.x());
  sum.block<3, 1>(3, 3) += weight * (-p.block<3, 1>(3, 0));
  sum.block<2, 1>(4, 4) += weight * (-p.block<2, 1>(4, 1));
  sum(5, 5) += weight * (-p(5, 2));
}

/// Evaluates the term for a source mean already moved to the world, y = R p + t.
inline IcpTerm evaluate_icp_term(const Eigen::Vector3d& q, const Eigen::Vector3d& y,
                                 const Eigen::Matrix3d& precision) {
  IcpTerm term;
  const Eigen::Vector3d r = q - y;
  term.energy = r.dot(precision * r);
  term.gradient = icp_gradient(y, r, precision);
  term.hessian = icp_hessian(y, precision);
  return term;
}

}  // namespace litamin2

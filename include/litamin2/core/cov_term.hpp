#pragma once
/// The covariance-shape (symmetric KL) term of LiTAMIN2, paper Eq. 4, for one correspondence:
///
///   f     = Tr(R Cp^-1 R^T Cq) + Tr(Cq^-1 R Cp R^T) - 6,    E_cov = f^2,
///
/// with derivatives with respect to the rotation update R <- exp([phi]x) R (t does not enter).
/// With M = R Cp^-1 R^T, N = R Cp R^T, B = Cq, D = Cq^-1 and U = [u]x, V = [v]x:
///   df/dphi = -2 vee(M B - B M + N D - D N)
///   d2f(u, v) = -Tr(U M V B) - Tr(V M U B) - Tr(U N V D) - Tr(V N U D)
///               + 1/2 Tr((U V + V U)(M B + B M)) + 1/2 Tr((U V + V U)(N D + D N)).
/// Since [u]x [v]x = v u^T - (u.v) I, the last two terms are u^T (S - Tr(S) I) v with S the
/// symmetric M B + B M (resp. N D + D N).
/// Then dE/dphi = 2 f df and d2E/dphi2 = 2 df df^T + 2 f d2f; the second part can be
/// indefinite, which CovHessian (registration_config.hpp) decides how to handle.
/// tests/unit/core_cost_terms_test.cpp checks all of this against finite differences.

#include "litamin2/core/so3.hpp"

#include <Eigen/Core>

namespace litamin2 {

struct CovShape {
  /// f, the bracket of Eq. 4 (zero when the two shapes agree).
  double f = 0.0;
  /// df/dphi.
  Eigen::Vector3d gradient;
  /// d2f/dphi2 (symmetric).
  Eigen::Matrix3d hessian;
};

namespace detail {
/// K_ij = Tr([e_i]x X [e_j]x Y) for the bilinear form Tr(U X V Y). Since ([e_i]x)_ab =
/// -eps_iab, K_ij = sum eps_iab eps_jcd X_bc Y_da, which has four non-zero terms: with
/// (a, b) = (i+1, i+2) or (i+2, i+1) and (c, d) = (j+1, j+2) or (j+2, j+1) (indices mod 3).
inline Eigen::Matrix3d skew_sandwich_traces(const Eigen::Matrix3d& x, const Eigen::Matrix3d& y) {
  Eigen::Matrix3d k;
  for (int i = 0; i < 3; ++i) {
    const int a = (i + 1) % 3, b = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int c = (j + 1) % 3, d = (j + 2) % 3;
      k(i, j) = x(b, c) * y(d, a) - x(b, d) * y(c, a) - x(a, c) * y(d, b) + x(a, d) * y(c, b);
    }
  }
  return k;
}
}  // namespace detail

/// f and its derivatives from M = R Cp^-1 R^T, N = R Cp R^T, B = Cq, D = Cq^-1.
inline CovShape evaluate_cov_shape(const Eigen::Matrix3d& m, const Eigen::Matrix3d& n,
                                   const Eigen::Matrix3d& b, const Eigen::Matrix3d& d) {
  CovShape shape;
  const Eigen::Matrix3d mb = m * b;
  const Eigen::Matrix3d nd = n * d;
  shape.f = mb.trace() + nd.trace() - 6.0;
  const Eigen::Matrix3d bm = mb.transpose();  // (M B)^T = B M for symmetric M, B
  const Eigen::Matrix3d dn = nd.transpose();
  shape.gradient = -2.0 * vee(mb - bm + nd - dn);
  const Eigen::Matrix3d k1 = detail::skew_sandwich_traces(m, b);
  const Eigen::Matrix3d k2 = detail::skew_sandwich_traces(n, d);
  const Eigen::Matrix3d s = mb + bm + nd + dn;
  shape.hessian =
      -(k1 + k1.transpose()) - (k2 + k2.transpose()) + s - s.trace() * Eigen::Matrix3d::Identity();
  return shape;
}

}  // namespace litamin2

#pragma once
/// The robust weight of LiTAMIN2 (paper Eq. 5): w = 1 - E / (E + sigma^2).
/// Note sigma squared: sigma_icp = 0.5 and sigma_cov = 3 are on the scale of sqrt(E).

namespace litamin2 {

inline double robust_weight(double energy, double sigma) {
  const double sigma_sq = sigma * sigma;
  return 1.0 - energy / (energy + sigma_sq);
}

/// The weight's own curvature in Newton's method (RegistrationConfig::robust_newton). Eq. 5's
/// w(E) = sigma^2 / (E + sigma^2) is the derivative of rho(E) = sigma^2 ln(1 + E / sigma^2), so
/// with g = dE/dxi and H = d2E/dxi2 the Hessian of rho(E(xi)) is w H + w'(E) g g^T, with
/// w' = -w^2 / sigma^2. This returns c >= 0 of the term -c g g^T: w^2 / sigma^2 up to
/// E = sigma^2, and w / (2 E) beyond. For the ICP term (H = 2 J^T C J, g = 2 J^T C r, E =
/// r^T C r) the correspondence's w H - c g g^T is J^T (2 w C - 4 c C r r^T C) J, which is
/// positive semi-definite exactly while c <= w / (2 E): past E = sigma^2 rho is not convex along
/// the residual, and the cap leaves that direction with zero curvature instead of negative.
inline double robust_weight_curvature(double energy, double sigma) {
  const double sigma_sq = sigma * sigma;
  const double w = robust_weight(energy, sigma);
  if (energy <= sigma_sq) return w * w / sigma_sq;
  return w / (2.0 * energy);
}

}  // namespace litamin2

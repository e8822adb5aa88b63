#pragma once
/// The robust weight of LiTAMIN2 (paper Eq. 5): w = 1 - E / (E + sigma^2).
/// Note sigma squared: sigma_icp = 0.5 and sigma_cov = 3 are on the scale of sqrt(E).

namespace litamin2 {

inline double robust_weight(double energy, double sigma) {
  const double sigma_sq = sigma * sigma;
  return 1.0 - energy / (energy + sigma_sq);
}

}  // namespace litamin2

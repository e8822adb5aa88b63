#pragma once
/// Relative pose error (RPE) over a fixed frame offset.

#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

namespace litamin2::eval {

/// Result of compute_rpe(). NaN values when pairs == 0.
struct RpeResult {
  /// Frame offset between the two poses of each pair.
  std::size_t delta = 1;
  /// Number of pairs (i, i + delta).
  std::size_t pairs = 0;
  /// RMSE and mean in metres of |translation of inv(inv(E_i) E_j) * inv(G_i) G_j|.
  double translation_rmse = 0.0;
  double translation_mean = 0.0;
  /// RMSE in degrees of the rotation angle of the same relative error.
  double rotation_rmse_deg = 0.0;
};

/// RPE of `estimate` against `ground_truth` over pairs (i, i + delta), i = 0, 1, ...
/// The relative error of a pair is inv(inv(E_i) * E_j) * (inv(G_i) * G_j), as in the KITTI metric
/// but per frame pair and not normalised by length. Throws std::invalid_argument if the sizes
/// differ or delta == 0.
RpeResult compute_rpe(const std::vector<Eigen::Isometry3d>& ground_truth,
                      const std::vector<Eigen::Isometry3d>& estimate, std::size_t delta = 1);

}  // namespace litamin2::eval

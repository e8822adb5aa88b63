#pragma once
/// Absolute trajectory error (ATE) after aligning the estimate to the ground truth.

#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

namespace litamin2::eval {

/// How the estimate is aligned to the ground truth before computing the ATE.
enum class AteAlignment {
  kNone,  ///< no alignment (estimate already in the ground-truth frame)
  kSE3,   ///< rotation + translation (Horn / Umeyama without scale)
  kSim3,  ///< rotation + translation + scale (Umeyama)
};

/// Result of compute_ate(). Errors are over all poses, after alignment.
struct AteResult {
  /// Number of pose pairs.
  std::size_t poses = 0;
  /// Position error statistics in metres: RMSE, mean, median and max of |p_gt - T(p_est)|.
  double translation_rmse = 0.0;
  double translation_mean = 0.0;
  double translation_median = 0.0;
  double translation_max = 0.0;
  /// RMSE in degrees of the angle of R_gt^T * R_align * R_est.
  double rotation_rmse_deg = 0.0;
  /// Rigid part of the alignment: aligned estimate pose = alignment * estimate pose (positions
  /// also multiplied by scale first for kSim3). Identity for kNone.
  Eigen::Isometry3d alignment = Eigen::Isometry3d::Identity();
  /// Scale of the alignment (1 unless kSim3).
  double scale = 1.0;
};

/// ATE of `estimate` against `ground_truth`, pose i paired with pose i. The alignment is fitted
/// on positions only (closed form, see umeyama_alignment()). Throws std::invalid_argument if the
/// sizes differ or the trajectories are empty.
AteResult compute_ate(const std::vector<Eigen::Isometry3d>& ground_truth,
                      const std::vector<Eigen::Isometry3d>& estimate,
                      AteAlignment alignment = AteAlignment::kSE3);

}  // namespace litamin2::eval

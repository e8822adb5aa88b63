#pragma once
/// LiTAMIN2 registration: Newton's method on sum w_icp E_icp + w_cov E_cov (paper Eq. 6) over
/// the source distributions and their nearest map distributions.

#include "litamin2/core/correspondence_search.hpp"
#include "litamin2/core/distribution.hpp"
#include "litamin2/core/nearest_cache.hpp"
#include "litamin2/core/registration_config.hpp"
#include "litamin2/core/so3.hpp"
#include "litamin2/core/voxel_map.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace litamin2 {

struct RegistrationResult {
  /// Source-to-map pose found.
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  /// Hessian of the cost at the last iteration, in the update's (phi, tau) coordinates.
  Matrix6d hessian = Matrix6d::Zero();
  /// Cost at the last iteration.
  double cost = 0.0;
  /// Correspondences at the last iteration.
  int correspondences = 0;
  /// Of these, those whose ICP energy was at most sigma_icp^2 (robust weight at least 1/2).
  int inliers = 0;
  /// Newton iterations run.
  int iterations = 0;
  /// The update fell below the tolerances within max_iterations.
  bool converged = false;
  /// False when there were too few correspondences or the system could not be solved; `pose`
  /// is then the last valid estimate.
  bool valid = false;
};

/// Cost, gradient and Hessian at one pose (exposed for tests and benchmarks).
struct CostEvaluation {
  double cost = 0.0;
  Vector6d gradient = Vector6d::Zero();
  /// Hessian with the Cov term's f d2f part.
  Matrix6d hessian = Matrix6d::Zero();
  /// The Cov term's f d2f part alone (rotation block), so the solver can drop it.
  Eigen::Matrix3d cov_curvature = Eigen::Matrix3d::Zero();
  /// The ICP term's robust-weight curvature, -sum w'(E) g g^T with each correspondence's
  /// factor capped where its cost is not convex (RegistrationConfig::robust_newton): positive
  /// semi-definite, subtracted from `hessian` for the Newton step. Not in `hessian`, which
  /// stays the weighted Gauss-Newton Hessian that the odometry covariance is made from.
  Matrix6d robust_curvature = Matrix6d::Zero();
  /// The ICP term's Hessian (Eq. 3, weight Eq. 5) of the correspondences the isotropy gate
  /// left out; summed only when evaluate_cost is asked to (with_gated_round).
  Matrix6d gated_round_hessian = Matrix6d::Zero();
  /// Correspondences used (after the registration gates).
  int correspondences = 0;
  /// Source distributions with a map distribution within the search radius (before the gates).
  int matched = 0;
  /// Correspondences whose ICP energy is at most sigma_icp^2 (robust weight at least 1/2).
  int inliers = 0;
};

/// The ICP term's gradient and Hessian (left update) summed with each correspondence's weight
/// times its source's time t, and the Hessian again with t^2: what a motion within the sweep
/// adds to the system (sweep_motion.hpp). The Cov term is left out.
struct TimeWeightedSums {
  Vector6d gradient = Vector6d::Zero();
  Matrix6d hessian = Matrix6d::Zero();
  Matrix6d hessian_sq = Matrix6d::Zero();
};

/// Evaluates the cost of `source` (in its own frame) against `map` at `pose`. With a cache
/// (one slot per source distribution, over the same search), correspondences are looked up
/// through it: the same ones, fewer searches. With `times` (one per source distribution) and
/// `timed`, also fills `timed`. With `with_gated_round`, also sums gated_round_hessian.
CostEvaluation evaluate_cost(const std::vector<Distribution>& source, const VoxelMap& map,
                             const CorrespondenceSearch& search, const Eigen::Isometry3d& pose,
                             const RegistrationConfig& config, NearestCache* cache = nullptr,
                             const std::vector<double>* times = nullptr,
                             TimeWeightedSums* timed = nullptr, bool with_gated_round = false);

/// How far `b` is from `a` in units of the re-grid tolerances (RegistrationConfig::
/// regrid_translation, regrid_rotation_deg): above 1 the scan is voxelised again at `b`.
double regrid_correction(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b,
                         const RegistrationConfig& config);

/// Whether a Newton step (rotation, translation) is below `factor` times the convergence
/// tolerances (RegistrationConfig::rotation_tolerance, translation_tolerance).
bool step_below(const Vector6d& xi, double factor, const RegistrationConfig& config);

/// Registers `source` to `map` starting from `initial`. With normal_only_ratio > 0, once the
/// step is below normal_only_start_factor times the tolerances within the re-grid tolerances
/// of `initial` (no re-grid follows), it takes normal_only_iterations more steps with a
/// plane's normal alone in the ICP gradient, and stops.
RegistrationResult register_distributions(const std::vector<Distribution>& source,
                                          const VoxelMap& map, const CorrespondenceSearch& search,
                                          const Eigen::Isometry3d& initial,
                                          const RegistrationConfig& config);

}  // namespace litamin2

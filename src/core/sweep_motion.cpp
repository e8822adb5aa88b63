#include "litamin2/core/sweep_motion.hpp"

#include "litamin2/core/config_error.hpp"
#include "litamin2/core/nearest_cache.hpp"
#include "litamin2/core/registration.hpp"
#include "litamin2/core/so3.hpp"
#include "litamin2/core/voxel_key.hpp"

#include <tsl/robin_map.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <string>

namespace litamin2 {
namespace {

void require(bool ok, const std::string& key, double value, const std::string& rule) {
  if (ok) return;
  throw ConfigError("deskew.sweep_motion." + key + ": " + std::to_string(value) + " is invalid (" +
                    rule + ")");
}

using Matrix12d = Eigen::Matrix<double, 12, 12>;
using Vector12d = Eigen::Matrix<double, 12, 1>;

/// The source with each distribution moved by Exp(t_i correction).
void move_within_sweep(const std::vector<Distribution>& source, const std::vector<double>& times,
                       const Twist& correction, std::vector<Distribution>& out) {
  out.resize(source.size());
  for (std::size_t i = 0; i < source.size(); ++i) {
    const Eigen::Isometry3d m = motion_after(correction, times[i]);
    const Eigen::Matrix3d& r = m.linear();
    Distribution& d = out[i];
    d = source[i];
    d.mean = m * source[i].mean;
    d.cov = r * source[i].cov * r.transpose();
    d.shape_cov = r * source[i].shape_cov * r.transpose();
    d.shape_cov_inv = r * source[i].shape_cov_inv * r.transpose();
  }
}

}  // namespace

void validate(const SweepMotionConfig& c) {
  require(std::isfinite(c.angular_sigma) && c.angular_sigma > 0.0, "angular_sigma", c.angular_sigma,
          "rad/s, > 0");
  require(std::isfinite(c.linear_sigma) && c.linear_sigma > 0.0, "linear_sigma", c.linear_sigma,
          "m/s, > 0");
  require(std::isfinite(c.max_time_spread_s) && c.max_time_spread_s > 0.0, "max_time_spread_s",
          c.max_time_spread_s, "seconds, > 0");
  require(c.max_iterations >= 1 && c.max_iterations <= 100, "max_iterations", c.max_iterations,
          "within [1, 100]");
  require(std::isfinite(c.min_speed_mps) && c.min_speed_mps >= 0.0, "min_speed_mps",
          c.min_speed_mps, "m/s, >= 0 (0: at any speed)");
}

DistributionTimes distribution_times(const PointCloud& scan, const std::vector<float>& times,
                                     const Voxelizer& voxelizer) {
  const VoxelizerConfig& config = voxelizer.config();
  const GridVoxels& voxels = voxelizer.last_voxels();
  tsl::robin_map<std::uint64_t, int, VoxelKeyHash> slot_of;
  slot_of.reserve(voxels.indices.size());
  for (std::size_t i = 0; i < voxels.indices.size(); ++i)
    slot_of.emplace(pack_voxel(voxels.indices[i]), static_cast<int>(i));
  std::vector<double> sum(voxels.indices.size(), 0.0);
  std::vector<double> sum_sq(voxels.indices.size(), 0.0);
  std::vector<int> count(voxels.indices.size(), 0);
  const double inv_size = 1.0 / config.voxel_size;
  const double min_range_sq = config.min_range * config.min_range;
  const double max_range_sq = config.max_range * config.max_range;
  double all_sum = 0.0;
  std::size_t all_count = 0;
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    const Eigen::Vector3d p = scan.points[i].cast<double>();
    const double range_sq = p.squaredNorm();
    if (!(range_sq >= min_range_sq && range_sq <= max_range_sq)) continue;
    all_sum += times[i];
    ++all_count;
    const auto it = slot_of.find(pack_voxel(voxel_index(voxels.grid_pose * p, inv_size)));
    if (it == slot_of.end()) continue;
    sum[it->second] += times[i];
    sum_sq[it->second] += static_cast<double>(times[i]) * times[i];
    ++count[it->second];
  }
  const double fallback = all_count > 0 ? all_sum / all_count : 0.0;
  DistributionTimes out;
  for (std::size_t i = 0; i < voxels.moments.size(); ++i) {
    if (voxels.moments[i].count < config.min_points) continue;
    if (count[i] == 0) {
      out.mean.push_back(fallback);
      out.spread.push_back(0.0);
      continue;
    }
    const double mean = sum[i] / count[i];
    out.mean.push_back(mean);
    out.spread.push_back(std::sqrt(std::max(0.0, sum_sq[i] / count[i] - mean * mean)));
  }
  return out;
}

SweepMotionResult register_with_sweep_motion(
    const std::vector<Distribution>& source, const DistributionTimes& distribution_times,
    const VoxelMap& map, const CorrespondenceSearch& search, const Eigen::Isometry3d& initial,
    const RegistrationConfig& registration, const SweepMotionConfig& config) {
  SweepMotionResult result;
  result.pose = initial;
  if (distribution_times.mean.size() != source.size() ||
      distribution_times.spread.size() != source.size())
    return result;
  // Time 0: not moved by the correction, no part in its terms.
  std::vector<double> times = distribution_times.mean;
  for (std::size_t i = 0; i < times.size(); ++i)
    if (!(distribution_times.spread[i] <= config.max_time_spread_s)) times[i] = 0.0;
  NearestCache cache(search, map.distributions(), source.size());
  RegistrationConfig active = registration;
  // This solver takes the weighted step (RegistrationConfig::robust_newton's curvature unused).
  active.robust_newton = false;
  // As register_distributions: the plane's normal alone in the gradient only once the step
  // without it is below normal_only_start_factor times the tolerances near `initial`, for
  // normal_only_iterations steps.
  active.normal_only_ratio = 0.0;
  int normal_only_steps = 0;
  std::vector<Distribution> moved;
  Vector6d prior_precision;
  prior_precision << Eigen::Vector3d::Constant(1.0 / (config.angular_sigma * config.angular_sigma)),
      Eigen::Vector3d::Constant(1.0 / (config.linear_sigma * config.linear_sigma));
  // A point's latest time in the sweep: the convergence test counts a correction step by it.
  const double span = times.empty() ? 0.0 : *std::max_element(times.begin(), times.end());
  for (int iteration = 0; iteration < config.max_iterations; ++iteration) {
    move_within_sweep(source, times, result.correction, moved);
    TimeWeightedSums timed;
    CostEvaluation eval =
        evaluate_cost(moved, map, search, result.pose, active, &cache, &times, &timed);
    // As register_distributions: where the gates leave too few correspondences, none.
    if ((active.max_isotropy < 1.0 || active.line_gate > 0.0) &&
        (eval.correspondences < registration.min_correspondences ||
         eval.correspondences < registration.isotropy_min_share * eval.matched)) {
      active.max_isotropy = 1.0;
      active.line_gate = 0.0;
      eval = evaluate_cost(moved, map, search, result.pose, active, &cache, &times, &timed);
    }
    result.iterations = iteration + 1;
    result.correspondences = eval.correspondences;
    if (eval.correspondences < registration.min_correspondences) {
      result.valid = false;
      return result;
    }
    const Matrix6d ad = adjoint(result.pose);
    const double dof = std::max(1.0, 3.0 * eval.correspondences - 12.0);
    const Vector6d prior = 2.0 * (eval.cost / dof) * prior_precision;
    Vector6d correction;
    correction << result.correction.angular, result.correction.linear;

    Matrix12d hessian;
    hessian.topLeftCorner<6, 6>() = eval.hessian;
    hessian.topRightCorner<6, 6>() = timed.hessian * ad;
    hessian.bottomLeftCorner<6, 6>() = ad.transpose() * timed.hessian;
    hessian.bottomRightCorner<6, 6>() = ad.transpose() * timed.hessian_sq * ad;
    hessian.bottomRightCorner<6, 6>().diagonal() += prior;
    Vector12d gradient;
    gradient.head<6>() = eval.gradient;
    gradient.tail<6>() = ad.transpose() * timed.gradient + prior.cwiseProduct(correction);

    Eigen::LDLT<Matrix12d> solver(hessian);
    if (solver.info() != Eigen::Success || (solver.vectorD().array() <= 0.0).any()) {
      // Where the Cov term's curvature makes the system indefinite, drop it (as Newton does).
      hessian.topLeftCorner<3, 3>() -= eval.cov_curvature;
      solver.compute(hessian);
      if (solver.info() != Eigen::Success || (solver.vectorD().array() <= 0.0).any()) {
        result.valid = false;
        return result;
      }
    }
    const Vector12d step = solver.solve(-gradient);
    if (!step.allFinite()) {
      result.valid = false;
      return result;
    }
    result.pose = apply_left_update(step.head<6>(), result.pose);
    result.correction.angular += step.segment<3>(6);
    result.correction.linear += step.tail<3>();
    result.valid = true;
    const bool refining = active.normal_only_ratio > 0.0;
    if (refining && ++normal_only_steps >= registration.normal_only_iterations) break;
    // The correction's step counted by what it moves a point over the sweep (span).
    Vector6d correction_step;
    correction_step << span * step.segment<3>(6), span * step.tail<3>();
    const auto below = [&](double factor) {
      return step_below(step.head<6>(), factor, registration) &&
             step_below(correction_step, factor, registration);
    };
    if (!refining && registration.normal_only_ratio > 0.0 &&
        below(registration.normal_only_start_factor) &&
        regrid_correction(initial, result.pose, registration) <= 1.0) {
      active.normal_only_ratio = registration.normal_only_ratio;
      continue;
    }
    if (below(1.0)) break;
  }
  return result;
}

}  // namespace litamin2

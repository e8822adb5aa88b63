#include "litamin2/core/registration.hpp"

#include "litamin2/core/cov_term.hpp"
#include "litamin2/core/icp_term.hpp"
#include "litamin2/core/information_share.hpp"
#include "litamin2/core/rank_one_update.hpp"
#include "litamin2/core/robust_weight.hpp"
#include "litamin2/core/so3.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

namespace litamin2 {
namespace {

/// Adds one correspondence's weighted terms (paper Eq. 6) to `out`.
void accumulate_correspondence(const Distribution& source, const Distribution& target,
                               const Eigen::Isometry3d& pose, const RegistrationConfig& config,
                               CostEvaluation& out, bool with_gated_round, double time = 0.0,
                               TimeWeightedSums* timed = nullptr) {
  const Eigen::Matrix3d& rotation = pose.linear();
  const Eigen::Vector3d y = pose * source.mean;
  const Eigen::Matrix3d rotated_cov = rotation * source.cov * rotation.transpose();

  ++out.matched;
  // Round combined distributions (not in the paper, RegistrationConfig::max_isotropy): their
  // mean depends on the viewpoint, which Eq. 3's normalised precision weights in every direction.
  if (config.max_isotropy < 1.0 &&
      combined_is_round(target.cov, rotated_cov, config.lambda, config.max_isotropy)) {
    if (with_gated_round) {
      // What the correspondence would add to the ICP term's Hessian (Eq. 3, weight Eq. 5).
      const IcpTerm round = evaluate_icp_term(
          target.mean, y, combined_precision(target.cov, rotated_cov, config.lambda));
      out.gated_round_hessian += robust_weight(round.energy, config.sigma_icp) * round.hessian;
    }
    return;
  }
  // Line-like combined distributions (not in the paper, RegistrationConfig::line_gate): two
  // parallel ring arcs, whose position across the line is partly the sensor's, not the world's.
  if (config.line_gate > 0.0 &&
      combined_is_line(target.cov, rotated_cov, config.lambda, config.line_gate)) {
    return;
  }
  // ICP term, Eq. 3, with its robust weight, Eq. 5.
  const Eigen::Matrix3d precision = combined_precision(target.cov, rotated_cov, config.lambda);
  const Eigen::Vector3d residual = target.mean - y;
  const double icp_energy = residual.dot(precision * residual);
  Vector6d gradient = icp_gradient(y, residual, precision);
  double hessian_weight = 1.0;
  // A plane's normal alone in the gradient (RegistrationConfig::normal_only_ratio, not in the
  // paper); the energy, its weight and the Hessian keep the whole precision. With
  // normal_only_thickness set (off by default), the plane's gradient and Hessian are weighted
  // by its thickness: Eq. 3's normalised precision weighs a rough plane's normal as much as a
  // crisp one's.
  if (config.normal_only_ratio > 0.0) {
    Eigen::Matrix3d normal_precision = precision;
    Eigen::Vector3d normal;
    if (keep_normal_only(normal_precision, config.normal_only_ratio, &normal)) {
      gradient = icp_gradient(y, residual, normal_precision);
      if (config.normal_only_thickness > 0.0) {
        const double thickness_sq = normal.dot((target.cov + rotated_cov) * normal);
        hessian_weight = plane_thickness_weight(thickness_sq, config.normal_only_thickness);
        gradient *= hessian_weight;
      }
    }
  }
  const double w_icp = robust_weight(icp_energy, config.sigma_icp);
  out.cost += w_icp * icp_energy;
  out.gradient += w_icp * gradient;
  // The Hessian's lower triangle only; evaluate_cost mirrors the sum.
  add_icp_hessian_lower(out.hessian, y, precision, w_icp * hessian_weight);
  if (config.robust_newton) {
    add_upper_rank_one(out.robust_curvature, gradient,
                       robust_weight_curvature(icp_energy, config.sigma_icp));
  }
  ++out.correspondences;
  if (w_icp >= 0.5) ++out.inliers;
  if (timed) {
    // The same term's derivatives times the source's time and its square (sweep_motion.hpp).
    const Matrix6d hessian = hessian_weight * icp_hessian(y, precision);
    timed->gradient += (w_icp * time) * gradient;
    timed->hessian += (w_icp * time) * hessian;
    timed->hessian_sq += (w_icp * time * time) * hessian;
  }
  if (config.mode != CostMode::kIcpCov) return;
  if (std::min(source.count, target.count) < config.cov_min_points) return;

  // Cov term, Eq. 4: E_cov = f^2 (or f, Table 1), rotation only.
  const Eigen::Matrix3d rotated_shape = rotation * source.shape_cov * rotation.transpose();
  const Eigen::Matrix3d rotated_shape_inv = rotation * source.shape_cov_inv * rotation.transpose();
  const CovShape shape =
      evaluate_cov_shape(rotated_shape_inv, rotated_shape, target.shape_cov, target.shape_cov_inv);
  const bool squared = config.cov_energy == CovEnergy::kSquared;
  const double energy = squared ? shape.f * shape.f : shape.f;
  const double w_cov = robust_weight(energy, config.sigma_cov);
  // dE/df and d2E/df2 of the chosen form: (2f, 2) or (1, 0).
  const double de_df = squared ? 2.0 * shape.f : 1.0;
  out.cost += w_cov * energy;
  out.gradient.head<3>() += w_cov * de_df * shape.gradient;
  if (squared) {
    out.hessian.topLeftCorner<3, 3>() += w_cov * 2.0 * shape.gradient * shape.gradient.transpose();
  }
  if (config.cov_hessian == CovHessian::kFull || !squared) {
    const Eigen::Matrix3d curvature = w_cov * de_df * shape.hessian;
    out.hessian.topLeftCorner<3, 3>() += curvature;
    out.cov_curvature += curvature;
  }
}

void add_into(TimeWeightedSums& total, const TimeWeightedSums& part) {
  total.gradient += part.gradient;
  total.hessian += part.hessian;
  total.hessian_sq += part.hessian_sq;
}

void add_into(CostEvaluation& total, const CostEvaluation& part) {
  total.cost += part.cost;
  total.gradient += part.gradient;
  total.hessian += part.hessian;
  total.cov_curvature += part.cov_curvature;
  total.robust_curvature += part.robust_curvature;
  total.gated_round_hessian += part.gated_round_hessian;
  total.correspondences += part.correspondences;
  total.matched += part.matched;
  total.inliers += part.inliers;
}

/// An LDLT that succeeded with a positive definite D.
bool positive_definite(const Eigen::LDLT<Matrix6d>& ldlt) {
  return ldlt.info() == Eigen::Success && ldlt.isPositive() && (ldlt.vectorD().array() > 0.0).all();
}

/// The robust Newton step may be at most this many times longer than the weighted step, in
/// rotation and in translation. Near the optimum the weighted (fixed-weight) iteration shrinks
/// its steps by a near-constant ratio r (0.3-0.4 on sparse scans), so the remaining distance is
/// its step over 1 - r, well within 3 steps; where many correspondences are past sigma the
/// capped curvature leaves H nearly singular, the robust step is much longer, and the weighted
/// one, which never increases the cost's majoriser, is taken instead.
constexpr double kMaxRobustStepRatio = 3.0;

/// The Newton step with the robust weight's curvature (RegistrationConfig::robust_newton):
/// solves (H - robust) xi = -g where that matrix is positive definite and the step passes
/// kMaxRobustStepRatio against `weighted_step` (H xi = -g); else returns `weighted_step`.
Vector6d robust_newton_step(const Matrix6d& hessian, const Matrix6d& robust_upper,
                            const Vector6d& gradient, const Vector6d& weighted_step) {
  const Matrix6d robust = robust_upper.selfadjointView<Eigen::Upper>();
  const Eigen::LDLT<Matrix6d> solver(hessian - robust);
  if (!positive_definite(solver)) return weighted_step;
  const Vector6d step = solver.solve(-gradient);
  if (!step.allFinite() ||
      step.head<3>().norm() > kMaxRobustStepRatio * weighted_step.head<3>().norm() ||
      step.tail<3>().norm() > kMaxRobustStepRatio * weighted_step.tail<3>().norm()) {
    return weighted_step;
  }
  return step;
}

}  // namespace

bool step_below(const Vector6d& xi, double factor, const RegistrationConfig& config) {
  return xi.head<3>().norm() < factor * config.rotation_tolerance &&
         xi.tail<3>().norm() < factor * config.translation_tolerance;
}

double regrid_correction(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b,
                         const RegistrationConfig& config) {
  const Eigen::Isometry3d delta = a.inverse() * b;
  return std::max(
      delta.translation().norm() / config.regrid_translation,
      Eigen::AngleAxisd(delta.linear()).angle() / (config.regrid_rotation_deg * M_PI / 180.0));
}

CostEvaluation evaluate_cost(const std::vector<Distribution>& source, const VoxelMap& map,
                             const CorrespondenceSearch& search, const Eigen::Isometry3d& pose,
                             const RegistrationConfig& config, NearestCache* cache,
                             const std::vector<double>* times, TimeWeightedSums* timed,
                             bool with_gated_round) {
  const double max_distance = config.max_correspondence_distance > 0.0
                                  ? config.max_correspondence_distance
                                  : map.voxel_size();
  const double max_distance_sq = max_distance * max_distance;
  const std::size_t block = static_cast<std::size_t>(std::max(1, config.block_size));
  const std::size_t num_blocks = (source.size() + block - 1) / block;
  std::vector<CostEvaluation> partial(num_blocks);
  const bool with_times = times && timed;
  std::vector<TimeWeightedSums> partial_timed(with_times ? num_blocks : 0);
  const auto& targets = map.distributions();

  // Fixed blocks, each summed in order, then the blocks summed in order: the result does not
  // depend on how many threads ran the blocks.
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, num_blocks, 1),
      [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t b = range.begin(); b != range.end(); ++b) {
          const std::size_t end = std::min(source.size(), (b + 1) * block);
          for (std::size_t i = b * block; i < end; ++i) {
            const Eigen::Vector3d query = pose * source[i].mean;
            const int match = cache ? cache->nearest(i, query, max_distance_sq)
                                    : search.nearest(query, max_distance_sq);
            if (match < 0) continue;
            if (with_times) {
              accumulate_correspondence(source[i], targets[match], pose, config, partial[b],
                                        with_gated_round, (*times)[i], &partial_timed[b]);
            } else {
              accumulate_correspondence(source[i], targets[match], pose, config, partial[b],
                                        with_gated_round);
            }
          }
        }
      },
      tbb::simple_partitioner());

  CostEvaluation total;
  for (const CostEvaluation& part : partial) add_into(total, part);
  // Only the lower triangle was summed (accumulate_correspondence); the upper is its mirror.
  total.hessian.triangularView<Eigen::StrictlyUpper>() = total.hessian.transpose();
  if (with_times) {
    *timed = TimeWeightedSums();
    for (const TimeWeightedSums& part : partial_timed) add_into(*timed, part);
  }
  return total;
}

RegistrationResult register_distributions(const std::vector<Distribution>& source,
                                          const VoxelMap& map, const CorrespondenceSearch& search,
                                          const Eigen::Isometry3d& initial,
                                          const RegistrationConfig& config) {
  RegistrationResult result;
  result.pose = initial;
  NearestCache cache(search, map.distributions(), source.size());
  // Where the isotropy and line gates leave too few correspondences (a scan of little flat
  // structure, or a sparse scan of mostly round voxels), the scan is registered with every
  // correspondence instead, as in the paper.
  RegistrationConfig active = config;
  // The plane's normal alone in the gradient (RegistrationConfig::normal_only_ratio) only once
  // the whole precision's step is below normal_only_start_factor times the tolerances, within
  // the re-grid tolerances of `initial` (the re-grid loop's last pass), for
  // normal_only_iterations weighted Newton steps: far from the optimum
  // the residuals along the planes are what turn the scan towards the map (with the normals
  // alone a scan started 10 deg off stayed 8 deg off). The Hessian keeps the whole precision:
  // along a street the walls' normals hold nothing forward, and a step from their gradient
  // alone would slide the scan along it.
  active.normal_only_ratio = 0.0;
  int normal_only_steps = 0;
  for (int iteration = 0; iteration < config.max_iterations; ++iteration) {
    // The isotropy gate only while what it keeps holds every direction of the pose
    // (RegistrationConfig::isotropy_min_information), judged at the first iteration.
    const bool judge_gate =
        iteration == 0 && active.max_isotropy < 1.0 && config.isotropy_min_information > 0.0;
    CostEvaluation eval = evaluate_cost(source, map, search, result.pose, active, &cache, nullptr,
                                        nullptr, judge_gate);
    if (judge_gate &&
        smallest_information_share(eval.hessian, eval.hessian + eval.gated_round_hessian) <
            config.isotropy_min_information) {
      active.max_isotropy = 1.0;
      eval = evaluate_cost(source, map, search, result.pose, active, &cache);
    }
    if ((active.max_isotropy < 1.0 || active.line_gate > 0.0) &&
        (eval.correspondences < config.min_correspondences ||
         eval.correspondences < config.isotropy_min_share * eval.matched)) {
      active.max_isotropy = 1.0;
      active.line_gate = 0.0;
      eval = evaluate_cost(source, map, search, result.pose, active, &cache);
    }
    result.iterations = iteration + 1;
    result.cost = eval.cost;
    result.correspondences = eval.correspondences;
    result.inliers = eval.inliers;
    result.hessian = eval.hessian;
    if (eval.correspondences < config.min_correspondences) {
      result.valid = false;
      return result;
    }
    // Newton step H xi = -g. Where the Cov term's curvature makes H indefinite, drop it.
    Matrix6d hessian = eval.hessian;
    Eigen::LDLT<Matrix6d> solver(hessian);
    if (!positive_definite(solver)) {
      hessian.topLeftCorner<3, 3>() -= eval.cov_curvature;
      result.hessian = hessian;
      solver.compute(hessian);
      if (solver.info() != Eigen::Success || (solver.vectorD().array() <= 0.0).any()) {
        result.valid = false;
        return result;
      }
    }
    Vector6d xi = solver.solve(-eval.gradient);
    // Near the optimum only (RegistrationConfig::robust_newton): within the re-grid tolerances.
    if (active.robust_newton && xi.allFinite() && xi.tail<3>().norm() < active.regrid_translation &&
        xi.head<3>().norm() < active.regrid_rotation_deg * (M_PI / 180.0)) {
      xi = robust_newton_step(hessian, eval.robust_curvature, eval.gradient, xi);
    }
    if (!xi.allFinite()) {
      result.valid = false;
      return result;
    }
    result.pose = apply_left_update(xi, result.pose);
    result.valid = true;
    const bool refining = active.normal_only_ratio > 0.0;
    if (refining && ++normal_only_steps >= config.normal_only_iterations) {
      result.converged = true;
      break;
    }
    if (!refining && config.normal_only_ratio > 0.0 &&
        step_below(xi, config.normal_only_start_factor, config) &&
        regrid_correction(initial, result.pose, config) <= 1.0) {
      active.normal_only_ratio = config.normal_only_ratio;
      active.robust_newton = false;
      continue;
    }
    if (step_below(xi, 1.0, config)) {
      result.converged = true;
      break;
    }
  }
  return result;
}

}  // namespace litamin2

#include "litamin2/mapping/loop_verifier.hpp"

#include "litamin2/core/correspondence_search.hpp"
#include "litamin2/core/registration.hpp"
#include "litamin2/mapping/fitness_scorer.hpp"

#include <cmath>

namespace litamin2::mapping {

Eigen::Isometry3d yaw_pose(double yaw) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return pose;
}

LoopVerification verify_loop(const std::vector<Distribution>& query, const VoxelMap& submap,
                             const Eigen::Isometry3d& initial, const LoopVerificationConfig& config,
                             double yaw_step) {
  LoopVerification out;
  if (query.size() < 20 || submap.distributions().size() < 20) {
    out.reason = "too few distributions";
    return out;
  }
  const auto search = make_correspondence_search(CorrespondenceMethod::kKdTree, submap);
  const FitnessScorer scorer(query, submap, *search);
  if (scorer.structure() < 20) {
    out.reason = "too little structure besides the ground";
    return out;
  }

  // Coarse search: the descriptor gives yaw to within a sector and says nothing about the
  // offset (and a pose estimate after drift is off by metres), so score a grid of yaws and
  // planar offsets around the initial pose on a subsample of the query.
  const CoarseAlignment coarse = coarse_alignment(scorer, submap.voxel_size(), initial, yaw_step);
  const Eigen::Isometry3d best = coarse.pose;
  const double best_score = coarse.fraction;

  // A wrong place rarely scores half the gate even with the coarse search's looser gate (half
  // a step); stop before the registration, which costs as much again.
  if (best_score < 0.5 * config.min_fitness) {
    out.fitness = best_score;
    out.reason = "coarse fitness " + std::to_string(best_score) + " below half the gate";
    return out;
  }

  // Fine: LiTAMIN2 ICP-term registration, first with a wide robust scale to pull in from the
  // coarse estimate, then with the odometry's scale for precision.
  RegistrationConfig wide;
  wide.mode = CostMode::kIcp;
  wide.sigma_icp = config.sigma_icp;
  wide.max_iterations = 50;
  wide.max_isotropy = config.max_isotropy;
  RegistrationResult result = register_distributions(query, submap, *search, best, wide);
  if (!result.valid) {
    out.reason = "registration failed";
    return out;
  }
  RegistrationConfig fine = wide;
  fine.sigma_icp = 0.1;
  const RegistrationResult refined =
      register_distributions(query, submap, *search, result.pose, fine);
  if (refined.valid) result = refined;

  const Fitness f = scorer.score(result.pose, config.fitness_distance, 1);
  out.relative = result.pose;
  out.fitness = f.fraction;
  out.rmse = f.rmse;
  if (f.fraction < config.min_fitness) {
    out.reason = "fitness " + std::to_string(f.fraction) + " below the gate";
  } else if (f.rmse > config.max_rmse) {
    out.reason = "rmse " + std::to_string(f.rmse) + " above the gate";
  } else {
    out.accepted = true;
  }
  return out;
}

}  // namespace litamin2::mapping

#include "litamin2/mapping/loop_verifier.hpp"

#include "litamin2/core/correspondence_search.hpp"
#include "litamin2/core/registration.hpp"

#include <Eigen/Eigenvalues>

#include <cmath>

namespace litamin2::mapping {
namespace {

struct Fitness {
  double fraction = 0.0;
  double rmse = 0.0;
};

/// Normal (smallest-eigenvalue axis) of a distribution's covariance.
Eigen::Vector3d normal_of(const Distribution& d) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(d.cov);
  return eigen.eigenvectors().col(0);
}

/// A roughly horizontal surface (road, ground): it matches the road of any other place, so
/// the fitness is computed without it.
bool horizontal(const Eigen::Vector3d& normal) {
  return std::abs(normal.z()) > 0.9;
}

/// The fitness of an alignment: among the query distributions that are not horizontal
/// surfaces (every `stride`-th only), the share whose nearest map distribution (within one
/// voxel) is closer than `gate` along that distribution's normal, and the RMS of those
/// distances. Distances along the normal, because two voxelisations of one wall put their
/// means up to a voxel apart within the wall's plane.
struct FitnessScorer {
  FitnessScorer(const std::vector<Distribution>& query, const VoxelMap& map,
                const CorrespondenceSearch& search)
      : query(query), map(map), search(search) {
    for (std::size_t i = 0; i < query.size(); ++i)
      if (!horizontal(normal_of(query[i]))) structure.push_back(i);
    for (const Distribution& d : map.distributions()) map_normals.push_back(normal_of(d));
  }

  Fitness score(const Eigen::Isometry3d& pose, double gate, std::size_t stride) const {
    const double radius_sq = map.voxel_size() * map.voxel_size();
    std::size_t tried = 0, inliers = 0;
    double sum_sq = 0.0;
    for (std::size_t k = 0; k < structure.size(); k += stride) {
      ++tried;
      const Eigen::Vector3d p = pose * query[structure[k]].mean;
      const int j = search.nearest(p, radius_sq);
      if (j < 0) continue;
      const auto index = static_cast<std::size_t>(j);
      const double distance = std::abs(map_normals[index].dot(p - map.distributions()[index].mean));
      if (distance > gate) continue;
      ++inliers;
      sum_sq += distance * distance;
    }
    Fitness f;
    if (tried > 0) f.fraction = static_cast<double>(inliers) / tried;
    if (inliers > 0) f.rmse = std::sqrt(sum_sq / inliers);
    return f;
  }

  const std::vector<Distribution>& query;
  const VoxelMap& map;
  const CorrespondenceSearch& search;
  std::vector<std::size_t> structure;
  std::vector<Eigen::Vector3d> map_normals;
};

}  // namespace

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
  if (scorer.structure.size() < 20) {
    out.reason = "too little structure besides the ground";
    return out;
  }

  // Coarse search: the descriptor gives yaw to within a sector and says nothing about the
  // offset (and a pose estimate after drift is off by metres), so score a grid of yaws and
  // planar offsets around the initial pose on a subsample of the query.
  const std::size_t stride = std::max<std::size_t>(1, scorer.structure.size() / 300);
  const double step = submap.voxel_size() / 2.0;
  Eigen::Isometry3d best = initial;
  double best_score = -1.0;
  for (double dyaw : {-yaw_step, 0.0, yaw_step}) {
    for (int ix = -4; ix <= 4; ++ix) {
      for (int iy = -4; iy <= 4; ++iy) {
        Eigen::Isometry3d pose = yaw_pose(dyaw) * initial;
        pose.translation() = initial.translation() + Eigen::Vector3d(ix * step, iy * step, 0.0);
        const Fitness f = scorer.score(pose, step / 2.0, stride);
        // Ties go to the smaller offset (the loop of the grid visits them in a fixed order).
        if (f.fraction > best_score + 1e-9) {
          best_score = f.fraction;
          best = pose;
        }
      }
    }
  }

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

#include "litamin2/mapping/fitness_scorer.hpp"

#include "litamin2/mapping/loop_verifier.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace litamin2::mapping {
namespace {

/// Normal (smallest-eigenvalue axis) of a distribution's covariance.
Eigen::Vector3d normal_of(const Distribution& d) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(d.cov);
  return eigen.eigenvectors().col(0);
}

/// A roughly horizontal surface (road, ground).
bool horizontal(const Eigen::Vector3d& normal) {
  return std::abs(normal.z()) > 0.9;
}

}  // namespace

FitnessScorer::FitnessScorer(const std::vector<Distribution>& query, const VoxelMap& map,
                             const CorrespondenceSearch& search)
    : query_(query), map_(map), search_(search) {
  for (std::size_t i = 0; i < query.size(); ++i)
    if (!horizontal(normal_of(query[i]))) structure_.push_back(i);
  for (const Distribution& d : map.distributions()) map_normals_.push_back(normal_of(d));
}

double FitnessScorer::normal_distance(const Eigen::Vector3d& p) const {
  const double radius_sq = map_.voxel_size() * map_.voxel_size();
  const int j = search_.nearest(p, radius_sq);
  if (j < 0) return -1.0;
  const auto index = static_cast<std::size_t>(j);
  return std::abs(map_normals_[index].dot(p - map_.distributions()[index].mean));
}

Fitness FitnessScorer::score(const Eigen::Isometry3d& pose, double gate, std::size_t stride) const {
  std::size_t tried = 0, inliers = 0;
  double sum_sq = 0.0;
  for (std::size_t k = 0; k < structure_.size(); k += stride) {
    ++tried;
    const double distance = normal_distance(pose * query_[structure_[k]].mean);
    if (distance < 0.0 || distance > gate) continue;
    ++inliers;
    sum_sq += distance * distance;
  }
  Fitness f;
  if (tried > 0) f.fraction = static_cast<double>(inliers) / tried;
  if (inliers > 0) f.rmse = std::sqrt(sum_sq / inliers);
  return f;
}

std::size_t FitnessScorer::inliers(const Eigen::Isometry3d& pose, double gate, std::size_t stride,
                                   std::size_t needed) const {
  std::size_t left = tried(stride), inliers = 0;
  for (std::size_t k = 0; k < structure_.size(); k += stride) {
    --left;
    const double distance = normal_distance(pose * query_[structure_[k]].mean);
    if (distance < 0.0 || distance > gate) {
      if (inliers + left < needed) return inliers;
      continue;
    }
    ++inliers;
  }
  return inliers;
}

CoarseAlignment coarse_alignment(const FitnessScorer& scorer, double voxel_size,
                                 const Eigen::Isometry3d& initial, double yaw_step, bool bounded) {
  const std::size_t stride = std::max<std::size_t>(1, scorer.structure() / 300);
  const double step = voxel_size / 2.0;
  const double gate = step / 2.0;
  const std::size_t tried = scorer.tried(stride);
  CoarseAlignment out;
  out.pose = initial;
  if (tried == 0) return out;
  auto pose_at = [&](double dyaw, int ix, int iy) {
    Eigen::Isometry3d pose = yaw_pose(dyaw) * initial;
    pose.translation() = initial.translation() + Eigen::Vector3d(ix * step, iy * step, 0.0);
    return pose;
  };
  // The initial pose's count first: the best has at least as many.
  std::size_t floor = 0;
  if (bounded) {
    floor = scorer.inliers(pose_at(0.0, 0, 0), gate, stride, 0);
    ++out.full_scores;
  }
  bool have_best = false;
  std::size_t best = 0;
  for (double dyaw : {-yaw_step, 0.0, yaw_step}) {
    for (int ix = -4; ix <= 4; ++ix) {
      for (int iy = -4; iy <= 4; ++iy) {
        const Eigen::Isometry3d pose = pose_at(dyaw, ix, iy);
        // Fractions are counts over `tried`: "more than the best by 1e-9" is "a larger count",
        // so ties go to the first pose (the smaller offset, as the loop visits them).
        const std::size_t needed = std::max(have_best ? best + 1 : 0, floor);
        std::size_t count = 0;
        if (bounded && dyaw == 0.0 && ix == 0 && iy == 0) {
          count = floor;
        } else {
          count = scorer.inliers(pose, gate, stride, bounded ? needed : 0);
          if (!bounded || count >= needed) ++out.full_scores;
        }
        if (count < needed || (have_best && count <= best)) continue;
        have_best = true;
        best = count;
        out.pose = pose;
      }
    }
  }
  out.fraction = static_cast<double>(best) / tried;
  return out;
}

}  // namespace litamin2::mapping

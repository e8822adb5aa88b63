#include "litamin2/core/global_pose_search.hpp"

#include "litamin2/core/config_error.hpp"
#include "litamin2/core/voxel_key.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace litamin2 {
namespace {

void require(bool ok, const std::string& key, double value, const std::string& rule) {
  if (ok) return;
  std::ostringstream out;
  out << "recovery.global_search." << key << ": " << value << " is invalid (" << rule << ")";
  throw ConfigError(out.str());
}

constexpr double kDegree = M_PI / 180.0;
/// Each level's steps are the previous level's divided by this.
constexpr double kRefinement = 4.0;
/// cos(25 deg): a distribution whose normal is this close to the vertical is a horizontal plane.
constexpr double kHorizontalNormal = 0.906;

/// `predicted` turned by `yaw` about the world's z at its own position, then placed at x, y.
Eigen::Isometry3d candidate_pose(const Eigen::Isometry3d& predicted, double x, double y,
                                 double yaw) {
  Eigen::Isometry3d pose = predicted;
  pose.linear() =
      Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix() * predicted.linear();
  pose.translation().x() = x;
  pose.translation().y() = y;
  return pose;
}

struct GridPoint {
  double x, y, yaw, score;
};

/// Scores every pose of the grid centred on (x0, y0, yaw0) with half-widths (hxy, hyaw) and
/// steps (sxy, syaw); appends them to `out`.
void score_grid(const PoseScorer& scorer, const std::vector<Eigen::Vector3d>& points,
                const Eigen::Isometry3d& predicted, double x0, double y0, double yaw0, double hxy,
                double hyaw, double sxy, double syaw, std::vector<GridPoint>& out) {
  const int nxy = static_cast<int>(std::floor(hxy / sxy + 1e-9));
  const int nyaw = static_cast<int>(std::floor(hyaw / syaw + 1e-9));
  for (int a = -nyaw; a <= nyaw; ++a) {
    const double yaw = yaw0 + a * syaw;
    for (int i = -nxy; i <= nxy; ++i) {
      for (int j = -nxy; j <= nxy; ++j) {
        const double x = x0 + i * sxy, y = y0 + j * sxy;
        out.push_back({x, y, yaw, scorer.score(points, candidate_pose(predicted, x, y, yaw))});
      }
    }
  }
}

/// The best `count` grid points, highest score first, each at least (sxy, syaw) from the ones
/// kept before it in x/y or yaw (non-maximum suppression).
std::vector<GridPoint> best_separated(std::vector<GridPoint> grid, int count, double sxy,
                                      double syaw) {
  std::sort(grid.begin(), grid.end(),
            [](const GridPoint& a, const GridPoint& b) { return a.score > b.score; });
  std::vector<GridPoint> kept;
  for (const GridPoint& g : grid) {
    if (static_cast<int>(kept.size()) >= count || !(g.score > 0.0)) break;
    bool near = false;
    for (const GridPoint& k : kept) {
      near |= std::abs(g.x - k.x) < sxy * 1.5 && std::abs(g.y - k.y) < sxy * 1.5 &&
              std::abs(g.yaw - k.yaw) < syaw * 1.5;
    }
    if (!near) kept.push_back(g);
  }
  return kept;
}

}  // namespace

void validate(const GlobalPoseSearchConfig& c) {
  require(std::isfinite(c.trigger_ratio) && c.trigger_ratio >= 0.0 && c.trigger_ratio < 1.0,
          "trigger_ratio", c.trigger_ratio, "0 (off) up to, not including, 1");
  require(std::isfinite(c.range_xy) && c.range_xy > 0.0 && c.range_xy <= 100.0, "range_xy",
          c.range_xy, "metres, above 0 and at most 100");
  require(std::isfinite(c.range_yaw_deg) && c.range_yaw_deg >= 0.0 && c.range_yaw_deg <= 180.0,
          "range_yaw_deg", c.range_yaw_deg, "degrees, 0 to 180");
  require(
      std::isfinite(c.coarse_step_xy) && c.coarse_step_xy >= 0.1 && c.coarse_step_xy <= c.range_xy,
      "coarse_step_xy", c.coarse_step_xy, "metres, at least 0.1 and at most range_xy");
  require(std::isfinite(c.coarse_step_yaw_deg) && c.coarse_step_yaw_deg >= 0.1 &&
              c.coarse_step_yaw_deg <= 90.0,
          "coarse_step_yaw_deg", c.coarse_step_yaw_deg, "degrees, 0.1 to 90");
  // Bounds the coarse grid: (2 range / step + 1)^2 positions times the yaw steps.
  const double positions = std::pow(2.0 * std::floor(c.range_xy / c.coarse_step_xy) + 1.0, 2.0) *
                           (2.0 * std::floor(c.range_yaw_deg / c.coarse_step_yaw_deg) + 1.0);
  require(positions <= 200000.0, "coarse_step_xy", c.coarse_step_xy,
          "the coarse grid may hold at most 200000 poses (range / step)");
  require(c.levels >= 1 && c.levels <= 4, "levels", c.levels, "1 to 4");
  require(c.candidates >= 1 && c.candidates <= 16, "candidates", c.candidates, "1 to 16");
  require(c.max_sources >= 16 && c.max_sources <= 10000, "max_sources", c.max_sources,
          "16 to 10000");
  require(std::isfinite(c.accept_ratio) && c.accept_ratio > 0.0 && c.accept_ratio <= 1.0,
          "accept_ratio", c.accept_ratio, "in (0, 1]");
}

std::vector<Eigen::Vector3d> search_points(const std::vector<Distribution>& source,
                                           const Eigen::Matrix3d& orientation, int max_sources) {
  std::vector<Eigen::Vector3d> constraining;
  constraining.reserve(source.size());
  for (const Distribution& d : source) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(d.cov);
    const Eigen::Vector3d normal = orientation * eig.eigenvectors().col(0);
    const bool flat = eig.eigenvalues()(0) < 0.1 * eig.eigenvalues()(1);
    if (flat && std::abs(normal.z()) > kHorizontalNormal) continue;
    constraining.push_back(d.mean);
  }
  if (static_cast<int>(constraining.size()) <= max_sources) return constraining;
  std::vector<Eigen::Vector3d> out;
  out.reserve(max_sources);
  const double stride = static_cast<double>(constraining.size()) / max_sources;
  for (int i = 0; i < max_sources; ++i)
    out.push_back(constraining[static_cast<std::size_t>(i * stride)]);
  return out;
}

PoseScorer::PoseScorer(const VoxelMap& map, double blur)
    : map_(map), inv_voxel_(1.0 / map.voxel_size()) {
  const std::vector<Distribution>& d = map.distributions();
  precisions_.resize(d.size());
  const Eigen::Matrix3d blur_cov = blur * blur * Eigen::Matrix3d::Identity();
  for (std::size_t i = 0; i < d.size(); ++i) precisions_[i] = (d[i].cov + blur_cov).inverse();
}

double PoseScorer::score(const std::vector<Eigen::Vector3d>& points,
                         const Eigen::Isometry3d& pose) const {
  if (points.empty()) return 0.0;
  const std::vector<Distribution>& d = map_.distributions();
  double sum = 0.0;
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d world = pose * p;
    const int k = map_.find(voxel_index(world, inv_voxel_));
    if (k < 0) continue;
    const Eigen::Vector3d r = world - d[k].mean;
    sum += std::exp(-0.5 * r.dot(precisions_[k] * r));
  }
  return sum / static_cast<double>(points.size());
}

std::vector<PoseCandidate> search_global_pose(const std::vector<Eigen::Vector3d>& points,
                                              const VoxelMap& map, const Eigen::Isometry3d& last,
                                              const Eigen::Isometry3d& predicted,
                                              const GlobalPoseSearchConfig& config) {
  std::vector<PoseCandidate> out;
  if (points.empty() || map.empty()) return out;
  double sxy = config.coarse_step_xy, syaw = config.coarse_step_yaw_deg * kDegree;
  // Level 0: the whole window around the last position, yaw around the prediction's.
  std::vector<GridPoint> grid;
  {
    const PoseScorer scorer(map, sxy);
    score_grid(scorer, points, predicted, last.translation().x(), last.translation().y(), 0.0,
               config.range_xy, config.range_yaw_deg * kDegree, sxy, syaw, grid);
  }
  std::vector<GridPoint> best = best_separated(std::move(grid), config.candidates, sxy, syaw);
  // Finer levels: a window of one coarser step around each candidate.
  for (int level = 1; level < config.levels && !best.empty(); ++level) {
    const double hxy = sxy, hyaw = syaw;
    sxy /= kRefinement;
    syaw /= kRefinement;
    const PoseScorer scorer(map, sxy);
    std::vector<GridPoint> refined;
    for (const GridPoint& b : best) {
      std::vector<GridPoint> local;
      score_grid(scorer, points, predicted, b.x, b.y, b.yaw, hxy, hyaw, sxy, syaw, local);
      const auto top = std::max_element(
          local.begin(), local.end(),
          [](const GridPoint& a, const GridPoint& c) { return a.score < c.score; });
      if (top != local.end()) refined.push_back(*top);
    }
    best = best_separated(std::move(refined), config.candidates, sxy, syaw);
  }
  for (const GridPoint& b : best)
    out.push_back({candidate_pose(predicted, b.x, b.y, b.yaw), b.score});
  return out;
}

}  // namespace litamin2

#include "litamin2/sim/road_network.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "litamin2/sim/grid.hpp"
#include "litamin2/sim/random.hpp"

namespace litamin2::sim {
namespace {

/// Calls visit(i) for every sample i indexed in the kCell cells that overlap the square of
/// half size `half` around (x, y); cells x outer, y inner, then in index order.
template <class Visit>
void for_each_sample_near(const std::unordered_map<std::int64_t, std::vector<int>>& grid, double x,
                          double y, double half, Visit&& visit) {
  const int cx0 = static_cast<int>(std::floor((x - half) / RoadNetwork::kCell));
  const int cx1 = static_cast<int>(std::floor((x + half) / RoadNetwork::kCell));
  const int cy0 = static_cast<int>(std::floor((y - half) / RoadNetwork::kCell));
  const int cy1 = static_cast<int>(std::floor((y + half) / RoadNetwork::kCell));
  for (int cx = cx0; cx <= cx1; ++cx) {
    for (int cy = cy0; cy <= cy1; ++cy) {
      const auto it = grid.find(cell_key(cx, cy));
      if (it == grid.end()) continue;
      for (int i : it->second) visit(i);
    }
  }
}

}  // namespace

RoadNetwork::RoadNetwork(const std::vector<std::vector<Eigen::Isometry3d>>& paths,
                         std::uint64_t seed, const WorldOptions& options)
    : opt_(options) {
  add_samples(paths);
  assign_districts(seed);
}

std::pair<double, int> RoadNetwork::nearest(double x, double y, double max_d) const {
  double best = max_d * max_d;
  int best_i = -1;
  const Eigen::Vector2d q(x, y);
  for_each_sample_near(grid_, x, y, max_d + max_segment_, [&](int i) {
    const PathSample& s = samples_[i];
    const Eigen::Vector2d a = s.p.head<2>();
    double d2;
    if (s.next >= 0) {
      const Eigen::Vector2d b = samples_[s.next].p.head<2>();
      const Eigen::Vector2d ab = b - a;
      const double l2 = ab.squaredNorm();
      const double t = l2 > 1e-12 ? std::clamp((q - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
      d2 = (a + t * ab - q).squaredNorm();
    } else {
      d2 = (a - q).squaredNorm();
    }
    if (d2 < best) {
      best = d2;
      best_i = i;
    }
  });
  return {best_i >= 0 ? std::sqrt(best) : max_d, best_i};
}

District RoadNetwork::district_near(double x, double y) const {
  const auto [d, i] = nearest(x, y, 200.0);
  (void)d;
  return i >= 0 ? samples_[i].district : District::kUrban;
}

bool RoadNetwork::at_arc(int p, double a, Eigen::Vector2d& pos, Eigen::Vector2d& tan,
                         District& dist) const {
  const auto& idx = path_samples_[p];
  if (idx.empty()) return false;
  const double first = samples_[idx.front()].arc, last = samples_[idx.back()].arc;
  if (a < first || a > last) return false;
  auto it = std::lower_bound(idx.begin(), idx.end(), a,
                             [&](int i, double v) { return samples_[i].arc < v; });
  if (it == idx.end()) --it;
  const int j = *it;
  const int i = it == idx.begin() ? j : *(it - 1);
  const double a0 = samples_[i].arc, a1 = samples_[j].arc;
  const double t = a1 > a0 ? (a - a0) / (a1 - a0) : 0.0;
  pos = (1 - t) * samples_[i].p.head<2>() + t * samples_[j].p.head<2>();
  const Eigen::Vector2d d = samples_[j].p.head<2>() - samples_[i].p.head<2>();
  tan = d.norm() > 1e-6 ? d.normalized() : samples_[j].t;
  dist = samples_[t < 0.5 ? i : j].district;
  return true;
}

// Ridge-regularised slopes, so the fit is exact on a path's own slope and flat across a
// straight road, also at the ends of a trajectory.
double RoadNetwork::road_height_raw(double x, double y) const {
  constexpr double kSigma = 10.0, kRadius = 30.0;
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  double wsum = 0.0;
  for_each_sample_near(grid_, x, y, kRadius, [&](int i) {
    const Eigen::Vector2d dxy = samples_[i].p.head<2>() - Eigen::Vector2d(x, y);
    const double d2 = dxy.squaredNorm();
    if (d2 > kRadius * kRadius) return;
    const double w = std::exp(-0.5 * d2 / (kSigma * kSigma));
    const Eigen::Vector3d u(1.0, dxy.x(), dxy.y());
    A += w * u * u.transpose();
    rhs += w * samples_[i].p.z() * u;
    wsum += w;
  });
  if (wsum > 1e-9) {
    A(1, 1) += 4.0 * wsum;
    A(2, 2) += 4.0 * wsum;
    return A.ldlt().solve(rhs)(0) - opt_.sensor_height;
  }
  // Far from every path: the nearest sample's height.
  const auto [d, i] = nearest(x, y, opt_.corridor_radius + 4.0 * opt_.tile_size);
  (void)d;
  if (i >= 0) return samples_[i].p.z() - opt_.sensor_height;
  return samples_.empty() ? -opt_.sensor_height : samples_.front().p.z() - opt_.sensor_height;
}

double RoadNetwork::road_height(double x, double y) const {
  const double gx = x / kLattice, gy = y / kLattice;
  const double fx = std::floor(gx), fy = std::floor(gy);
  const double tx = gx - fx, ty = gy - fy;
  const double h00 = road_height_raw(fx * kLattice, fy * kLattice);
  const double h10 = road_height_raw((fx + 1) * kLattice, fy * kLattice);
  const double h01 = road_height_raw(fx * kLattice, (fy + 1) * kLattice);
  const double h11 = road_height_raw((fx + 1) * kLattice, (fy + 1) * kLattice);
  return (1 - ty) * ((1 - tx) * h00 + tx * h10) + ty * ((1 - tx) * h01 + tx * h11);
}

std::unordered_set<std::int64_t> RoadNetwork::corridor_tiles() const {
  std::unordered_set<std::int64_t> tiles;
  Eigen::Vector2d last(std::numeric_limits<double>::infinity(), 0);
  for (const auto& s : samples_) {
    if ((s.p.head<2>() - last).norm() < 5.0) continue;
    last = s.p.head<2>();
    for_each_cell_near(last, opt_.corridor_radius, opt_.tile_size,
                       [&](int x, int y) { tiles.insert(cell_key(x, y)); });
  }
  return tiles;
}

void RoadNetwork::add_samples(const std::vector<std::vector<Eigen::Isometry3d>>& paths) {
  for (std::size_t p = 0; p < paths.size(); ++p) {
    const auto& poses = paths[p];
    std::vector<int> idx;
    double since = 0.0, arc = 0.0;
    for (std::size_t k = 0; k < poses.size(); ++k) {
      if (k > 0) {
        const double step = (poses[k].translation() - poses[k - 1].translation()).norm();
        since += step;
        arc += step;
      }
      if (k != 0 && since < kSampleSpacing && k + 1 != poses.size()) continue;
      if (k != 0 && since < 1e-3) continue;
      since = 0.0;
      PathSample s;
      s.p = poses[k].translation();
      Eigen::Vector2d h = poses[k].linear().col(0).head<2>();
      s.t = h.norm() > 1e-6 ? h.normalized() : Eigen::Vector2d(1, 0);
      // Speed over +-10 frames at 10 Hz.
      const std::size_t k0 = k >= 10 ? k - 10 : 0, k1 = std::min(poses.size() - 1, k + 10);
      double dist = 0.0;
      for (std::size_t j = k0; j < k1; ++j) {
        dist += (poses[j + 1].translation() - poses[j].translation()).norm();
      }
      s.speed = k1 > k0 ? dist / (0.1 * static_cast<double>(k1 - k0)) : 0.0;
      s.arc = arc;
      s.path = static_cast<int>(p);
      if (!idx.empty()) {
        samples_[idx.back()].next = static_cast<int>(samples_.size());
        max_segment_ = std::max(max_segment_, (s.p - samples_[idx.back()].p).head<2>().norm());
      }
      idx.push_back(static_cast<int>(samples_.size()));
      samples_.push_back(s);
    }
    path_samples_.push_back(std::move(idx));
  }
  for (std::size_t i = 0; i < samples_.size(); ++i) {
    const auto& p = samples_[i].p;
    grid_[cell_key(static_cast<int>(std::floor(p.x() / kCell)),
                   static_cast<int>(std::floor(p.y() / kCell)))]
        .push_back(static_cast<int>(i));
  }
}

void RoadNetwork::assign_districts(std::uint64_t seed) {
  for (std::size_t p = 0; p < path_samples_.size(); ++p) {
    Rng rng(hash_combine(hash_combine(seed, 0xd157), p));
    double block_end = -1.0;
    District current = District::kUrban;
    for (int i : path_samples_[p]) {
      PathSample& s = samples_[i];
      if (s.arc >= block_end) {
        block_end = s.arc + rng.uniform(60.0, 180.0);
        const auto& w = opt_.district_weights;
        const double r = rng.uniform() * std::max(1e-12, w[0] + w[1] + w[2]);
        current = r < w[0]          ? District::kUrban
                  : r < w[0] + w[1] ? District::kSuburban
                                    : District::kGreen;
      }
      s.district = s.speed > opt_.open_speed ? District::kOpen : current;
    }
  }
}

}  // namespace litamin2::sim

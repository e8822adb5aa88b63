#include "litamin2/sim/scan_statistics.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unordered_map>

namespace litamin2::sim {
namespace {

std::uint64_t voxel_key(const Eigen::Vector3f& p, double size) {
  const auto ix = static_cast<std::int64_t>(std::floor(p.x() / size));
  const auto iy = static_cast<std::int64_t>(std::floor(p.y() / size));
  const auto iz = static_cast<std::int64_t>(std::floor(p.z() / size));
  return (static_cast<std::uint64_t>(ix & 0x1fffff) << 42) |
         (static_cast<std::uint64_t>(iy & 0x1fffff) << 21) |
         static_cast<std::uint64_t>(iz & 0x1fffff);
}

std::unordered_map<std::uint64_t, std::size_t> voxel_counts(const PointCloud& cloud, double size) {
  std::unordered_map<std::uint64_t, std::size_t> counts;
  for (const auto& p : cloud.points) ++counts[voxel_key(p, size)];
  return counts;
}

/// Median of the values (nearest rank); 0 for none.
template <typename T>
double median_of(std::vector<T> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return static_cast<double>(v[v.size() / 2]);
}

double median_count(const std::unordered_map<std::uint64_t, std::size_t>& counts) {
  std::vector<std::size_t> v;
  v.reserve(counts.size());
  for (const auto& [k, c] : counts) {
    (void)k;
    v.push_back(c);
  }
  return median_of(std::move(v));
}

/// Moments of the points in one 3 m voxel and whether they come from one ring.
struct VoxelMoments {
  std::size_t n = 0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
  int ring = -1;
  bool one_ring = true;
};

/// Ring of each point: the index of the nearest elevation (elevations sorted top first).
std::vector<int> assign_rings(const PointCloud& cloud, const std::vector<double>& elevations_deg) {
  std::vector<int> rings(cloud.size(), 0);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3d p = cloud.points[i].cast<double>();
    const double e = std::atan2(p.z(), std::hypot(p.x(), p.y())) * 180.0 / M_PI;
    int best = 0;
    for (std::size_t r = 1; r < elevations_deg.size(); ++r) {
      if (std::abs(elevations_deg[r] - e) < std::abs(elevations_deg[best] - e)) {
        best = static_cast<int>(r);
      }
    }
    rings[i] = best;
  }
  return rings;
}

/// Median azimuth step over all rings and the robust roughness of the lowest ring.
void ring_geometry(const PointCloud& cloud, const std::vector<int>& rings, std::size_t n_rings,
                   ScanStatistics& s) {
  std::vector<std::vector<std::pair<double, double>>> by_ring(n_rings);  // (azimuth, range)
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3d p = cloud.points[i].cast<double>();
    by_ring[rings[i]].push_back({std::atan2(p.y(), p.x()) * 180.0 / M_PI, p.norm()});
  }
  std::vector<double> steps;
  for (auto& ring : by_ring) {
    std::sort(ring.begin(), ring.end());
    for (std::size_t k = 1; k < ring.size(); ++k) {
      const double d = ring[k].first - ring[k - 1].first;
      if (d > 1e-6) steps.push_back(d);
    }
  }
  s.azimuth_step_deg = median_of(steps);
  const auto& low = by_ring.back();
  if (low.size() < 3 || s.azimuth_step_deg <= 0) return;
  std::vector<double> second;
  const double max_gap = 2.5 * s.azimuth_step_deg;
  for (std::size_t k = 1; k + 1 < low.size(); ++k) {
    if (low[k].first - low[k - 1].first > max_gap || low[k + 1].first - low[k].first > max_gap) {
      continue;
    }
    second.push_back(std::abs(low[k - 1].second - 2.0 * low[k].second + low[k + 1].second));
  }
  s.lowest_ring_roughness = 1.4826 * median_of(second) / std::sqrt(6.0);
}

/// Trimmed least-squares plane z = a + b x + c y through the low points near the sensor.
void fit_ground(const PointCloud& cloud, ScanStatistics& s) {
  std::vector<Eigen::Vector3d> pts;
  for (const auto& pf : cloud.points) {
    const Eigen::Vector3d p = pf.cast<double>();
    const double h = std::hypot(p.x(), p.y());
    if (h >= 4.0 && h < 16.0 && p.z() < -1.0) pts.push_back(p);
  }
  if (pts.size() < 50) return;
  std::vector<bool> inlier(pts.size(), true);
  Eigen::Vector3d abc = Eigen::Vector3d::Zero();
  for (int it = 0; it < 6; ++it) {
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    Eigen::Vector3d b = Eigen::Vector3d::Zero();
    std::size_t used = 0;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      if (!inlier[i]) continue;
      const Eigen::Vector3d v(1.0, pts[i].x(), pts[i].y());
      A += v * v.transpose();
      b += v * pts[i].z();
      ++used;
    }
    if (used < 10) return;
    abc = A.ldlt().solve(b);
    std::vector<double> res(pts.size());
    for (std::size_t i = 0; i < pts.size(); ++i) {
      res[i] = std::abs(pts[i].z() - (abc[0] + abc[1] * pts[i].x() + abc[2] * pts[i].y()));
    }
    const double threshold = it < 3 ? 2.5 * median_of(res) : 0.15;
    for (std::size_t i = 0; i < pts.size(); ++i) inlier[i] = res[i] < threshold;
  }
  double sq = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (!inlier[i]) continue;
    const double r = pts[i].z() - (abc[0] + abc[1] * pts[i].x() + abc[2] * pts[i].y());
    sq += r * r;
    ++n;
  }
  if (n == 0) return;
  s.ground_height = -abc[0];
  s.ground_pitch_deg = std::atan(abc[1]) * 180.0 / M_PI;
  s.ground_roll_deg = std::atan(abc[2]) * 180.0 / M_PI;
  s.ground_residual = std::sqrt(sq / static_cast<double>(n));
}

}  // namespace

ScanStatistics compute_scan_statistics(const PointCloud& cloud,
                                       const std::vector<double>& elevations_deg) {
  ScanStatistics s;
  s.points = cloud.size();
  if (cloud.empty()) return s;
  const auto v1 = voxel_counts(cloud, 1.0);
  const auto v2 = voxel_counts(cloud, 2.0);
  s.voxels_1m = v1.size();
  s.voxels_2m = v2.size();
  s.median_points_1m = median_count(v1);
  s.median_points_2m = median_count(v2);
  const auto v3 = voxel_counts(cloud, 3.0);
  s.voxels_3m = v3.size();
  s.median_points_3m = median_count(v3);
  for (const auto& [k, c] : v3) {
    (void)k;
    if (c >= 5) ++s.voxels_3m_min5;
  }
  s.voxels_5m = voxel_counts(cloud, 5.0).size();

  std::vector<double> r;
  r.reserve(cloud.size());
  for (const auto& p : cloud.points) r.push_back(p.cast<double>().norm());
  std::sort(r.begin(), r.end());
  s.range_median = r[r.size() / 2];
  s.range_p90 = r[std::min(r.size() - 1, static_cast<std::size_t>(0.9 * r.size()))];
  s.range_max = r.back();
  for (double x : r) {
    std::size_t bin = 0;
    while (bin + 1 < kRangeBins && x >= kRangeBinEdges[bin]) ++bin;
    s.range_histogram[bin] += 1.0 / static_cast<double>(r.size());
    if (x < 2.0) ++s.near_2m;
  }

  std::vector<int> rings;
  if (!elevations_deg.empty()) {
    std::vector<double> sorted = elevations_deg;
    std::sort(sorted.begin(), sorted.end(), std::greater<double>());
    rings = assign_rings(cloud, sorted);
    s.ring_points.assign(sorted.size(), 0);
    for (int ring : rings) ++s.ring_points[ring];
    ring_geometry(cloud, rings, sorted.size(), s);
  }
  std::unordered_map<std::uint64_t, VoxelMoments> moments;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    VoxelMoments& m = moments[voxel_key(cloud.points[i], 3.0)];
    const Eigen::Vector3d p = cloud.points[i].cast<double>();
    ++m.n;
    m.sum += p;
    m.outer += p * p.transpose();
    if (!rings.empty()) {
      if (m.ring < 0) m.ring = rings[i];
      if (m.ring != rings[i]) m.one_ring = false;
    }
  }
  std::size_t counted = 0, single = 0, linear = 0, planar = 0, round = 0, horizontal = 0;
  for (const auto& [k, m] : moments) {
    (void)k;
    if (m.n < 5) continue;
    ++counted;
    if (!rings.empty() && m.one_ring) ++single;
    const Eigen::Vector3d mean = m.sum / static_cast<double>(m.n);
    const Eigen::Matrix3d cov = m.outer / static_cast<double>(m.n) - mean * mean.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
    const Eigen::Vector3d ev = eig.eigenvalues();  // increasing
    if (ev[1] < 0.01 * ev[2]) {
      ++linear;
    } else if (ev[0] < 0.01 * ev[1]) {
      ++planar;
      if (std::abs(eig.eigenvectors().col(0).z()) > std::cos(15.0 * M_PI / 180.0)) ++horizontal;
    }
    if (ev[0] > 0.05 * ev[2]) ++round;
  }
  if (counted > 0) {
    s.single_ring_3m = static_cast<double>(single) / static_cast<double>(counted);
    s.linear_3m = static_cast<double>(linear) / static_cast<double>(counted);
    s.planar_3m = static_cast<double>(planar) / static_cast<double>(counted);
    s.round_3m = static_cast<double>(round) / static_cast<double>(counted);
    s.horizontal_3m = static_cast<double>(horizontal) / static_cast<double>(counted);
  }
  fit_ground(cloud, s);
  return s;
}

std::vector<std::pair<std::string, double>> statistic_rows(const ScanStatistics& s) {
  std::vector<std::pair<std::string, double>> rows = {
      {"points", static_cast<double>(s.points)},
      {"1 m voxels", static_cast<double>(s.voxels_1m)},
      {"2 m voxels", static_cast<double>(s.voxels_2m)},
      {"3 m voxels", static_cast<double>(s.voxels_3m)},
      {"3 m voxels >= 5 pts", static_cast<double>(s.voxels_3m_min5)},
      {"5 m voxels", static_cast<double>(s.voxels_5m)},
      {"median pts / 1 m voxel", s.median_points_1m},
      {"median pts / 2 m voxel", s.median_points_2m},
      {"median pts / 3 m voxel", s.median_points_3m},
      {"3 m single-ring share", s.single_ring_3m},
      {"3 m line-like share", s.linear_3m},
      {"3 m planar share", s.planar_3m},
      {"3 m horizontal-plane share", s.horizontal_3m},
      {"3 m round share (> 0.05)", s.round_3m},
      {"hits < 2 m", static_cast<double>(s.near_2m)},
      {"range median [m]", s.range_median},
      {"range p90 [m]", s.range_p90},
      {"range max [m]", s.range_max},
  };
  for (std::size_t b = 0; b < kRangeBins; ++b) {
    char label[48];
    if (b == 0) {
      std::snprintf(label, sizeof(label), "range < %g m share", kRangeBinEdges[0]);
    } else if (b + 1 == kRangeBins) {
      std::snprintf(label, sizeof(label), "range >= %g m share", kRangeBinEdges[b - 1]);
    } else {
      std::snprintf(label, sizeof(label), "range %g-%g m share", kRangeBinEdges[b - 1],
                    kRangeBinEdges[b]);
    }
    rows.push_back({label, s.range_histogram[b]});
  }
  if (!s.ring_points.empty()) {
    for (std::size_t k = 0; k < s.ring_points.size(); ++k) {
      rows.push_back(
          {"ring " + std::to_string(k) + " points", static_cast<double>(s.ring_points[k])});
    }
    rows.push_back({"azimuth step [deg]", s.azimuth_step_deg});
    rows.push_back({"lowest ring roughness [m]", s.lowest_ring_roughness});
  }
  rows.push_back({"ground height [m]", s.ground_height});
  rows.push_back({"ground pitch [deg]", s.ground_pitch_deg});
  rows.push_back({"ground roll [deg]", s.ground_roll_deg});
  rows.push_back({"ground residual [m]", s.ground_residual});
  return rows;
}

void ScanStatisticsMean::add(const ScanStatistics& s) {
  ++count_;
  for (const auto& [label, value] : statistic_rows(s)) {
    auto it = std::find_if(sums_.begin(), sums_.end(),
                           [&](const auto& row) { return std::get<0>(row) == label; });
    if (it == sums_.end()) {
      sums_.emplace_back(label, value, 1);
    } else {
      std::get<1>(*it) += value;
      ++std::get<2>(*it);
    }
  }
}

std::vector<std::pair<std::string, double>> ScanStatisticsMean::rows() const {
  std::vector<std::pair<std::string, double>> out;
  out.reserve(sums_.size());
  for (const auto& [label, sum, n] : sums_) out.push_back({label, sum / static_cast<double>(n)});
  return out;
}

double ScanStatisticsMean::mean(const std::string& label) const {
  for (const auto& [l, sum, n] : sums_) {
    if (l == label) return sum / static_cast<double>(n);
  }
  return 0.0;
}

std::string to_string(const ScanStatistics& s) {
  char buf[256];
  std::snprintf(buf, sizeof(buf),
                "points=%zu v1=%zu v2=%zu v3=%zu v3>=5=%zu v5=%zu r50=%.1f r90=%.1f rmax=%.1f",
                s.points, s.voxels_1m, s.voxels_2m, s.voxels_3m, s.voxels_3m_min5, s.voxels_5m,
                s.range_median, s.range_p90, s.range_max);
  return buf;
}

}  // namespace litamin2::sim

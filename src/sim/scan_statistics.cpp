#include "litamin2/sim/scan_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unordered_map>

namespace litamin2::sim {
namespace {

std::unordered_map<std::uint64_t, std::size_t> voxel_counts(const PointCloud& cloud, double size) {
  std::unordered_map<std::uint64_t, std::size_t> counts;
  for (const auto& p : cloud.points) {
    const auto ix = static_cast<std::int64_t>(std::floor(p.x() / size));
    const auto iy = static_cast<std::int64_t>(std::floor(p.y() / size));
    const auto iz = static_cast<std::int64_t>(std::floor(p.z() / size));
    const std::uint64_t key = (static_cast<std::uint64_t>(ix & 0x1fffff) << 42) |
                              (static_cast<std::uint64_t>(iy & 0x1fffff) << 21) |
                              static_cast<std::uint64_t>(iz & 0x1fffff);
    ++counts[key];
  }
  return counts;
}

}  // namespace

ScanStatistics compute_scan_statistics(const PointCloud& cloud) {
  ScanStatistics s;
  s.points = cloud.size();
  if (cloud.empty()) return s;
  s.voxels_1m = voxel_counts(cloud, 1.0).size();
  s.voxels_2m = voxel_counts(cloud, 2.0).size();
  const auto v3 = voxel_counts(cloud, 3.0);
  s.voxels_3m = v3.size();
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
  return s;
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

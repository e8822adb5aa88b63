#include "litamin2/mapping/place_descriptor.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace litamin2::mapping {

PlaceDescriptor make_place_descriptor(const std::vector<Distribution>& distributions,
                                      const PlaceRecognitionConfig& config) {
  PlaceDescriptor d;
  d.rings = config.rings;
  d.sectors = config.sectors;
  d.cells.assign(static_cast<std::size_t>(d.rings * d.sectors), 0);
  const double ring_width = config.max_range / d.rings;
  const double sector_width = 2.0 * M_PI / d.sectors;
  for (const Distribution& dist : distributions) {
    const Eigen::Vector3d& p = dist.mean;
    const double range = std::hypot(p.x(), p.y());
    if (range >= config.max_range) continue;
    const int ring = std::min(d.rings - 1, static_cast<int>(range / ring_width));
    const double azimuth = std::atan2(p.y(), p.x()) + M_PI;  // [0, 2 pi]
    const int sector = std::min(d.sectors - 1, static_cast<int>(azimuth / sector_width));
    const double steps = std::round((p.z() + kDescriptorHeightOffset) / kDescriptorHeightStep);
    const auto height = static_cast<std::uint8_t>(std::clamp(steps, 1.0, 255.0));
    std::uint8_t& cell = d.cells[static_cast<std::size_t>(ring * d.sectors + sector)];
    cell = std::max(cell, height);
  }
  d.ring_key.assign(static_cast<std::size_t>(d.rings), 0.0f);
  for (int r = 0; r < d.rings; ++r) {
    int occupied = 0;
    for (int s = 0; s < d.sectors; ++s) occupied += d.cells[r * d.sectors + s] > 0;
    d.ring_key[r] = static_cast<float>(occupied) / d.sectors;
  }
  return d;
}

namespace {

/// What the comparison derives from a descriptor's cells: per sector the mean of its cells
/// (shifts with the yaw: aligns two descriptors before the full comparison) and the Euclidean
/// norm of its column.
struct SectorKeys {
  explicit SectorKeys(const PlaceDescriptor& d)
      : mean(static_cast<std::size_t>(d.sectors), 0.0), norm(static_cast<std::size_t>(d.sectors)) {
    for (int s = 0; s < d.sectors; ++s) {
      double sum = 0.0, sum_sq = 0.0;
      for (int r = 0; r < d.rings; ++r) {
        const double v = d.cells[r * d.sectors + s];
        sum += v;
        sum_sq += v * v;
      }
      mean[s] = sum / d.rings;
      norm[s] = std::sqrt(sum_sq);
    }
  }
  std::vector<double> mean;
  std::vector<double> norm;
};

}  // namespace

DescriptorMatch match_descriptors(const PlaceDescriptor& query, const PlaceDescriptor& candidate) {
  DescriptorMatch best;
  const int rings = query.rings;
  const int sectors = query.sectors;
  if (candidate.rings != rings || candidate.sectors != sectors) return best;
  const SectorKeys qk(query), ck(candidate);
  // A point at azimuth theta in the query frame is at theta + yaw in the candidate's frame,
  // so query column s is compared with candidate column s + shift.
  int aligned = 0;
  double aligned_error = std::numeric_limits<double>::infinity();
  for (int shift = 0; shift < sectors; ++shift) {
    double error = 0.0;
    for (int s = 0; s < sectors; ++s) {
      const double d = qk.mean[s] - ck.mean[(s + shift) % sectors];
      error += d * d;
    }
    if (error < aligned_error) {
      aligned_error = error;
      aligned = shift;
    }
  }
  const int search = std::min(kDescriptorShiftSearch, sectors / 2);
  for (int offset = -search; offset <= search; ++offset) {
    const int shift = ((aligned + offset) % sectors + sectors) % sectors;
    double sum = 0.0;
    int columns = 0;
    for (int s = 0; s < sectors; ++s) {
      const int c = (s + shift) % sectors;
      const double qn = qk.norm[s], cn = ck.norm[c];
      if (qn == 0.0 || cn == 0.0) continue;
      double dot = 0.0;
      for (int r = 0; r < rings; ++r)
        dot += double(query.cells[r * sectors + s]) * candidate.cells[r * sectors + c];
      sum += 1.0 - dot / (qn * cn);
      ++columns;
    }
    if (columns == 0) continue;
    const double distance = sum / columns;
    if (distance < best.distance) {
      best.distance = distance;
      best.yaw = shift * 2.0 * M_PI / sectors;
      if (best.yaw > M_PI) best.yaw -= 2.0 * M_PI;
    }
  }
  return best;
}

double ring_key_distance(const PlaceDescriptor& a, const PlaceDescriptor& b) {
  double sum = 0.0;
  const std::size_t n = std::min(a.ring_key.size(), b.ring_key.size());
  for (std::size_t i = 0; i < n; ++i) {
    const double d = double(a.ring_key[i]) - b.ring_key[i];
    sum += d * d;
  }
  return sum;
}

}  // namespace litamin2::mapping

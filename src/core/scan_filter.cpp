#include "litamin2/core/scan_filter.hpp"

#include <cmath>

namespace litamin2 {

namespace {

/// Writes into `out` the points of `scan` that `drop` does not take, with their intensities and
/// times.
template <typename Drop>
void keep_points(const PointCloud& scan, Drop drop, PointCloud& out) {
  out.points.clear();
  out.intensities.clear();
  out.times.clear();
  out.points.reserve(scan.points.size());
  const bool with_intensity = scan.has_intensities();
  const bool with_times = scan.has_times();
  if (with_intensity) out.intensities.reserve(scan.intensities.size());
  if (with_times) out.times.reserve(scan.times.size());
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    if (drop(scan.points[i])) continue;
    out.points.push_back(scan.points[i]);
    if (with_intensity) out.intensities.push_back(scan.intensities[i]);
    if (with_times) out.times.push_back(scan.times[i]);
  }
}

}  // namespace

void remove_box(const PointCloud& scan, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                PointCloud& out) {
  keep_points(
      scan, [&](const Eigen::Vector3f& p) { return inside_box(p, lo, hi); }, out);
}

EgoLearner::EgoLearner(const ScanFilterConfig& config) : config_(config) {
  side_ = 2 * static_cast<int>(std::ceil(config_.auto_radius / config_.auto_cell));
  const std::size_t cells = static_cast<std::size_t>(side_) * side_ * side_;
  hits_.assign(cells, 0);
  ego_.assign(cells, 0);
  seen_.assign(cells, -1);
}

int EgoLearner::cell_of(const Eigen::Vector3f& p) const {
  if (!(p.squaredNorm() < config_.auto_radius * config_.auto_radius)) return -1;  // also NaN
  const double inv = 1.0 / config_.auto_cell;
  const int half = side_ / 2;
  const int x = static_cast<int>(std::floor(p.x() * inv)) + half;
  const int y = static_cast<int>(std::floor(p.y() * inv)) + half;
  const int z = static_cast<int>(std::floor(p.z() * inv)) + half;
  if (x < 0 || y < 0 || z < 0 || x >= side_ || y >= side_ || z >= side_) return -1;
  return (z * side_ + y) * side_ + x;
}

void EgoLearner::observe(const PointCloud& scan) {
  if (decided_) return;
  for (const Eigen::Vector3f& p : scan.points) {
    const int cell = cell_of(p);
    if (cell < 0 || seen_[cell] == counted_) continue;
    seen_[cell] = counted_;
    ++hits_[cell];
  }
  if (++counted_ < config_.auto_scans) return;
  const double needed = config_.auto_min_share * counted_;
  for (std::size_t i = 0; i < hits_.size(); ++i) {
    ego_[i] = hits_[i] >= needed ? 1 : 0;
    ego_cells_ += ego_[i];
  }
  decided_ = true;
}

bool EgoLearner::is_ego(const Eigen::Vector3f& p) const {
  if (!decided_ || ego_cells_ == 0) return false;
  const int cell = cell_of(p);
  return cell >= 0 && ego_[cell] != 0;
}

bool EgoLearner::filter(const PointCloud& scan, PointCloud& out) const {
  if (!decided_ || ego_cells_ == 0) return false;
  keep_points(
      scan, [this](const Eigen::Vector3f& p) { return is_ego(p); }, out);
  return true;
}

}  // namespace litamin2

#include "litamin2/mapping/map_tile.hpp"

#include "litamin2/core/voxel_key.hpp"
#include "litamin2/mapping/distribution_moments.hpp"

#include <algorithm>
#include <cmath>

namespace litamin2::mapping {

namespace {

std::int32_t tile_index(double metres, double tile_size) {
  return static_cast<std::int32_t>(std::floor(metres / tile_size));
}

}  // namespace

TileKey TileGeometry::tile_of_voxel(const VoxelIndex& voxel) const {
  const double size = voxels.voxel_size;
  return {tile_index((voxel.x() + 0.5) * size, tile_size),
          tile_index((voxel.y() + 0.5) * size, tile_size)};
}

void TileGeometry::tile_range(double x0, double y0, double x1, double y1, TileKey& lo,
                              TileKey& hi) const {
  lo = {tile_index(std::min(x0, x1), tile_size), tile_index(std::min(y0, y1), tile_size)};
  hi = {tile_index(std::max(x0, x1), tile_size), tile_index(std::max(y0, y1), tile_size)};
}

std::size_t MapTile::bytes() const {
  return sizeof(MapTile) + voxels_.capacity() * sizeof(Voxel) +
         index_.bucket_count() * (sizeof(std::uint64_t) + 2 * sizeof(std::uint32_t));
}

bool MapTile::apply(std::uint64_t voxel_key, const VoxelMoments& moments, int sign) {
  const auto it = index_.find(voxel_key);
  if (sign > 0) {
    if (it == index_.end()) {
      index_.emplace(voxel_key, static_cast<std::uint32_t>(voxels_.size()));
      voxels_.push_back({voxel_key, moments});
    } else {
      voxels_[it->second].moments.merge(moments);
    }
    return true;
  }
  if (it == index_.end()) return false;
  const std::uint32_t i = it->second;
  VoxelMoments& v = voxels_[i].moments;
  if (v.count < moments.count) return false;
  v.count -= moments.count;
  v.sum -= moments.sum;
  v.sum_sq -= moments.sum_sq;
  if (v.count == 0) {
    index_.erase(it);
    if (i + 1 != voxels_.size()) {
      voxels_[i] = std::move(voxels_.back());
      index_[voxels_[i].key] = i;
    }
    voxels_.pop_back();
  }
  return true;
}

std::vector<Distribution> MapTile::distributions(const TileGeometry& geometry) const {
  std::vector<const Voxel*> valid;
  valid.reserve(voxels_.size());
  for (const Voxel& v : voxels_) {
    if (v.moments.count >= geometry.voxels.min_points) valid.push_back(&v);
  }
  std::sort(valid.begin(), valid.end(),
            [](const Voxel* a, const Voxel* b) { return a->key < b->key; });
  std::vector<Distribution> out;
  out.reserve(valid.size());
  for (const Voxel* v : valid)
    out.push_back(v->moments.to_distribution(geometry.voxels.regularizer));
  return out;
}

TileSummary MapTile::summary(const TileGeometry& geometry) const {
  TileSummary s;
  s.key = key_;
  s.keyframes = keyframes_;
  std::vector<std::pair<std::uint64_t, Eigen::Vector3f>> means;
  for (const Voxel& v : voxels_) {
    if (v.moments.count < geometry.voxels.min_points) continue;
    const Eigen::Vector3d mean = v.moments.origin + v.moments.sum / v.moments.count;
    means.emplace_back(v.key, mean.cast<float>());
  }
  s.distributions = static_cast<std::int64_t>(means.size());
  if (means.empty()) return s;
  std::sort(means.begin(), means.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  s.min_bound = s.max_bound = means.front().second;
  for (const auto& [key, m] : means) {
    s.min_bound = s.min_bound.cwiseMin(m);
    s.max_bound = s.max_bound.cwiseMax(m);
  }
  const std::size_t n = std::min(TileSummary::kSampleMeans, means.size());
  for (std::size_t i = 0; i < n; ++i) s.sample.push_back(means[i * means.size() / n].second);
  return s;
}

MapTile MapTile::restore(TileKey key, std::int64_t keyframes, std::vector<Voxel> voxels) {
  MapTile t(key);
  t.keyframes_ = keyframes;
  t.voxels_ = std::move(voxels);
  t.index_.reserve(t.voxels_.size());
  for (std::size_t i = 0; i < t.voxels_.size(); ++i)
    t.index_.emplace(t.voxels_[i].key, static_cast<std::uint32_t>(i));
  return t;
}

std::vector<FusedMoment> fused_moments(const std::vector<Distribution>& distributions,
                                       const Eigen::Isometry3d& pose,
                                       const TileGeometry& geometry) {
  const GridVoxels moments = moments_of(distributions);
  const Eigen::Matrix3d r = pose.linear();
  const Eigen::Vector3d t = pose.translation();
  const double size = geometry.voxels.voxel_size;
  const double inv_size = 1.0 / size;
  std::vector<FusedMoment> out;
  out.reserve(moments.moments.size());
  for (const VoxelMoments& m : moments.moments) {
    const VoxelIndex voxel = voxel_index(r * m.origin + t, inv_size);
    const Eigen::Vector3d centre = (voxel.cast<double>() + Eigen::Vector3d::Constant(0.5)) * size;
    out.push_back({geometry.tile_of_voxel(voxel), pack_voxel(voxel), m.transformed(r, t, centre)});
  }
  return out;
}

}  // namespace litamin2::mapping

#include "litamin2/mapping/segment_voxels.hpp"

#include "litamin2/core/voxel_key.hpp"

namespace litamin2::mapping {

std::size_t SegmentVoxels::apply(const std::vector<Distribution>& distributions,
                                 const Eigen::Isometry3d& relative, double voxel_size, int sign) {
  TileGeometry geometry;
  geometry.voxels.voxel_size = voxel_size;
  std::size_t mismatched = 0;
  for (const FusedMoment& m : fused_moments(distributions, relative, geometry)) {
    const auto it = voxels_.find(m.voxel);
    if (sign > 0) {
      if (it == voxels_.end())
        voxels_.emplace(m.voxel, m.moments);
      else
        it.value().merge(m.moments);
      continue;
    }
    if (it == voxels_.end() || it->second.count < m.moments.count) {
      ++mismatched;
      continue;
    }
    VoxelMoments& v = it.value();
    v.count -= m.moments.count;
    v.sum -= m.moments.sum;
    v.sum_sq -= m.moments.sum_sq;
    if (v.count == 0) voxels_.erase(it);
  }
  return mismatched;
}

std::size_t SegmentVoxels::bytes() const {
  return sizeof(SegmentVoxels) +
         voxels_.bucket_count() * (sizeof(std::uint64_t) + sizeof(VoxelMoments) + 8);
}

std::vector<FusedMoment> placed_moments(const SegmentVoxels& segment,
                                        const Eigen::Isometry3d& frame,
                                        const TileGeometry& geometry) {
  const Eigen::Matrix3d r = frame.linear();
  const Eigen::Vector3d t = frame.translation();
  const double size = geometry.voxels.voxel_size;
  const double inv_size = 1.0 / size;
  std::vector<FusedMoment> out;
  out.reserve(segment.voxels().size());
  for (const auto& [key, m] : segment.voxels()) {
    const Eigen::Vector3d mean = m.origin + m.sum / static_cast<double>(m.count);
    const VoxelIndex voxel = voxel_index(r * mean + t, inv_size);
    const Eigen::Vector3d centre = (voxel.cast<double>() + Eigen::Vector3d::Constant(0.5)) * size;
    out.push_back({geometry.tile_of_voxel(voxel), pack_voxel(voxel), m.transformed(r, t, centre)});
  }
  return out;
}

}  // namespace litamin2::mapping

#include "litamin2/mapping/segment_voxels.hpp"

#include "litamin2/core/voxel_key.hpp"

#include <algorithm>

namespace litamin2::mapping {

namespace {

SegmentVoxels::Voxel compact(std::uint64_t key, const VoxelMoments& m) {
  SegmentVoxels::Voxel v;
  v.key = key;
  v.count = m.count;
  for (int i = 0; i < 3; ++i) v.sum[i] = m.sum(i);
  for (int i = 0; i < 6; ++i) v.sum_sq[i] = m.sum_sq(i);
  return v;
}

void add_to(SegmentVoxels::Voxel& v, const SegmentVoxels::Voxel& d, int sign) {
  v.count += sign * d.count;
  for (int i = 0; i < 3; ++i) v.sum[i] += sign * d.sum[i];
  for (int i = 0; i < 6; ++i) v.sum_sq[i] += sign * d.sum_sq[i];
}

}  // namespace

VoxelMoments SegmentVoxels::moments(const Voxel& v, double voxel_size) {
  VoxelMoments m;
  m.origin = (unpack_voxel(v.key).cast<double>() + Eigen::Vector3d::Constant(0.5)) * voxel_size;
  m.count = v.count;
  m.sum = Eigen::Vector3d(v.sum[0], v.sum[1], v.sum[2]);
  for (int i = 0; i < 6; ++i) m.sum_sq(i) = v.sum_sq[i];
  return m;
}

std::size_t SegmentVoxels::apply(const std::vector<Distribution>& distributions,
                                 const Eigen::Isometry3d& relative, double voxel_size, int sign) {
  TileGeometry geometry;
  geometry.voxels.voxel_size = voxel_size;
  // The keyframe's moments by segment voxel (several of its distributions may share one).
  std::vector<Voxel> delta;
  for (const FusedMoment& m : fused_moments(distributions, relative, geometry))
    delta.push_back(compact(m.voxel, m.moments));
  std::stable_sort(delta.begin(), delta.end(),
                   [](const Voxel& a, const Voxel& b) { return a.key < b.key; });
  std::vector<Voxel> merged_delta;
  for (const Voxel& d : delta) {
    if (!merged_delta.empty() && merged_delta.back().key == d.key)
      add_to(merged_delta.back(), d, +1);
    else
      merged_delta.push_back(d);
  }
  // Merged into the sorted voxels.
  std::vector<Voxel> out;
  out.reserve(voxels_.size() + (sign > 0 ? merged_delta.size() : 0));
  std::size_t mismatched = 0;
  auto v = voxels_.begin();
  for (const Voxel& d : merged_delta) {
    while (v != voxels_.end() && v->key < d.key) out.push_back(*v++);
    const bool present = v != voxels_.end() && v->key == d.key;
    if (sign > 0) {
      if (present) {
        out.push_back(*v++);
        add_to(out.back(), d, +1);
      } else {
        out.push_back(d);
      }
      continue;
    }
    if (!present || v->count < d.count) {
      ++mismatched;
      continue;
    }
    Voxel r = *v++;
    add_to(r, d, -1);
    if (r.count > 0) out.push_back(r);
  }
  out.insert(out.end(), v, voxels_.end());
  voxels_ = std::move(out);
  return mismatched;
}

SegmentVoxels SegmentVoxels::of(std::vector<Voxel> voxels) {
  SegmentVoxels out;
  out.voxels_ = std::move(voxels);
  return out;
}

std::size_t SegmentVoxels::bytes() const {
  return sizeof(SegmentVoxels) + voxels_.capacity() * sizeof(Voxel);
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
  for (const SegmentVoxels::Voxel& v : segment.voxels()) {
    const VoxelMoments m = SegmentVoxels::moments(v, size);
    const Eigen::Vector3d mean = m.origin + m.sum / static_cast<double>(m.count);
    const VoxelIndex voxel = voxel_index(r * mean + t, inv_size);
    const Eigen::Vector3d centre = (voxel.cast<double>() + Eigen::Vector3d::Constant(0.5)) * size;
    out.push_back({geometry.tile_of_voxel(voxel), pack_voxel(voxel), m.transformed(r, t, centre)});
  }
  return out;
}

}  // namespace litamin2::mapping

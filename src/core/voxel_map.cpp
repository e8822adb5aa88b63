#include "litamin2/core/voxel_map.hpp"

#include "litamin2/core/voxel_moments.hpp"
#include "litamin2/core/voxel_voting.hpp"

#include <tsl/robin_map.h>

namespace litamin2 {

struct VoxelMap::Cells {
  struct Cell {
    std::uint64_t key = 0;
    VoxelMoments moments;
    /// The distribution of `moments`, recomputed only when points were added.
    Distribution cached;
    /// Points were added since `cached` was computed.
    bool dirty = true;
    /// Index into distributions_, or -1 while the voxel has too few points.
    int distribution = -1;
  };
  /// Cells in insertion order (so iteration, and thus results, are deterministic).
  std::vector<Cell> cells;
  tsl::robin_map<std::uint64_t, int, VoxelKeyHash> cell_of_key;

  /// The cell of voxel `index` (edge `voxel_size`), added empty (its moments' origin at the
  /// voxel's centre) if it is not there yet; marked dirty, as the caller adds to it.
  Cell& dirty_cell(const VoxelIndex& index, double voxel_size) {
    const std::uint64_t key = pack_voxel(index);
    const auto [it, inserted] = cell_of_key.try_emplace(key, static_cast<int>(cells.size()));
    if (inserted) {
      Cell& cell = cells.emplace_back();
      cell.key = key;
      cell.moments.origin = (index.cast<double>() + Eigen::Vector3d::Constant(0.5)) * voxel_size;
    }
    Cell& cell = cells[it->second];
    cell.dirty = true;
    return cell;
  }
};

VoxelMap::VoxelMap(const VoxelizerConfig& voxels, const VoxelMapConfig& config)
    : voxels_(voxels), config_(config), cells_(std::make_unique<Cells>()) {}
VoxelMap::~VoxelMap() = default;
VoxelMap::VoxelMap(VoxelMap&&) noexcept = default;
VoxelMap& VoxelMap::operator=(VoxelMap&&) noexcept = default;

void VoxelMap::insert(const PointCloud& scan, const Eigen::Isometry3d& pose) {
  Cells& c = *cells_;
  vote_points(scan, pose, voxels_, [&](const VoxelIndex& index) -> VoxelMoments& {
    return c.dirty_cell(index, voxels_.voxel_size).moments;
  });
  rebuild_distributions();
}

void VoxelMap::insert(const GridVoxels& voxels, const Eigen::Isometry3d& pose) {
  merge_grid_voxels(voxels, pose);
  rebuild_distributions();
}

void VoxelMap::remove_far(const Eigen::Vector3d& position) {
  if (drop_far_cells(position)) rebuild_distributions();
}

void VoxelMap::add_keyframe(const GridVoxels& voxels, const Eigen::Isometry3d& pose) {
  merge_grid_voxels(voxels, pose);
  drop_far_cells(pose.translation());
  rebuild_distributions();
}

void VoxelMap::add_distributions(const std::vector<Distribution>& distributions,
                                 const Eigen::Isometry3d& pose) {
  const Eigen::Matrix3d r = pose.linear();
  const Eigen::Vector3d t = pose.translation();
  const double size = voxels_.voxel_size;
  const double inv_size = 1.0 / size;
  Cells& c = *cells_;
  for (const Distribution& dist : distributions) {
    if (dist.count < 1) continue;
    const Eigen::Vector3d mean = r * dist.mean + t;
    Cells::Cell& cell = c.dirty_cell(voxel_index(mean, inv_size), size);
    cell.moments.merge(VoxelMoments::of_distribution(mean, r * dist.cov * r.transpose(), dist.count,
                                                     cell.moments.origin));
  }
  drop_far_cells(t);
  rebuild_distributions();
}

void VoxelMap::merge_grid_voxels(const GridVoxels& voxels, const Eigen::Isometry3d& pose) {
  const Eigen::Isometry3d correction = pose * voxels.grid_pose.inverse();
  const Eigen::Matrix3d r = correction.linear();
  const Eigen::Vector3d t = correction.translation();
  const double size = voxels_.voxel_size;
  const double inv_size = 1.0 / size;
  Cells& c = *cells_;
  for (const VoxelMoments& moments : voxels.moments) {
    const Eigen::Vector3d mean = moments.origin + moments.sum / moments.count;
    Cells::Cell& cell = c.dirty_cell(voxel_index(r * mean + t, inv_size), size);
    cell.moments.merge(moments.transformed(r, t, cell.moments.origin));
  }
}

bool VoxelMap::drop_far_cells(const Eigen::Vector3d& position) {
  Cells& c = *cells_;
  const double radius_sq = config_.radius * config_.radius;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < c.cells.size(); ++i) {
    if ((c.cells[i].moments.origin - position).squaredNorm() <= radius_sq) {
      if (kept != i) c.cells[kept] = std::move(c.cells[i]);
      ++kept;
    }
  }
  if (kept == c.cells.size()) return false;
  c.cells.resize(kept);
  c.cell_of_key.clear();
  for (std::size_t i = 0; i < c.cells.size(); ++i) {
    c.cell_of_key.emplace(c.cells[i].key, static_cast<int>(i));
  }
  return true;
}

void VoxelMap::rebuild_distributions() {
  distributions_.clear();
  for (Cells::Cell& cell : cells_->cells) {
    cell.distribution = -1;
    if (cell.moments.count < voxels_.min_points) continue;
    if (cell.dirty) {
      cell.cached = cell.moments.to_distribution(voxels_.regularizer);
      cell.dirty = false;
    }
    cell.distribution = static_cast<int>(distributions_.size());
    distributions_.push_back(cell.cached);
  }
}

int VoxelMap::find(const VoxelIndex& index) const {
  const auto it = cells_->cell_of_key.find(pack_voxel(index));
  return it == cells_->cell_of_key.end() ? -1 : cells_->cells[it->second].distribution;
}

std::size_t VoxelMap::num_voxels() const {
  return cells_->cells.size();
}

}  // namespace litamin2

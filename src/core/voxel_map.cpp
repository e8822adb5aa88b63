#include "litamin2/core/voxel_map.hpp"

#include "litamin2/core/voxel_moments.hpp"
#include "litamin2/core/voxel_voting.hpp"

#include <tsl/robin_map.h>

namespace litamin2 {

struct VoxelMap::Cells {
  struct Cell {
    std::uint64_t key = 0;
    VoxelMoments moments;
    /// Points were added since the cell's distribution was computed (it is on `dirty_list`).
    bool dirty = false;
    /// The slot holds a voxel (false once dropped, until a new voxel reuses it).
    bool live = false;
    /// Index into distributions_, or -1 while the voxel has too few points.
    int distribution = -1;
  };
  /// Slots of voxels; a dropped voxel's slot is reused by the next new one, so the slots of
  /// the voxels kept never move.
  std::vector<Cell> cells;
  std::vector<int> free_slots;
  tsl::robin_map<std::uint64_t, int, VoxelKeyHash> cell_of_key;
  /// Slots whose moments changed since the distributions were last brought up to date, in
  /// the order they first changed (so the results are deterministic).
  std::vector<int> dirty_list;
  /// distribution_cell[i] is the slot of distributions_[i].
  std::vector<int> distribution_cell;

  /// The cell of voxel `index` (edge `voxel_size`), added empty (its moments' origin at the
  /// voxel's centre) if it is not there yet; marked dirty, as the caller adds to it.
  Cell& dirty_cell(const VoxelIndex& index, double voxel_size) {
    const std::uint64_t key = pack_voxel(index);
    const int next_slot = free_slots.empty() ? static_cast<int>(cells.size()) : free_slots.back();
    const auto [it, inserted] = cell_of_key.try_emplace(key, next_slot);
    if (inserted) {
      if (free_slots.empty()) {
        cells.emplace_back();
      } else {
        free_slots.pop_back();
      }
      Cell& cell = cells[next_slot];
      cell = Cell();
      cell.key = key;
      cell.live = true;
      cell.moments.origin = (index.cast<double>() + Eigen::Vector3d::Constant(0.5)) * voxel_size;
    }
    const int slot = it->second;
    Cell& cell = cells[slot];
    if (!cell.dirty) {
      cell.dirty = true;
      dirty_list.push_back(slot);
    }
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
  bool dropped = false;
  for (std::size_t slot = 0; slot < c.cells.size(); ++slot) {
    Cells::Cell& cell = c.cells[slot];
    if (!cell.live || (cell.moments.origin - position).squaredNorm() <= radius_sq) continue;
    if (cell.distribution >= 0) remove_distribution(cell.distribution);
    c.cell_of_key.erase(cell.key);
    cell.live = false;
    cell.dirty = false;  // a stale entry of dirty_list is skipped
    c.free_slots.push_back(static_cast<int>(slot));
    dropped = true;
  }
  return dropped;
}

void VoxelMap::remove_distribution(int index) {
  Cells& c = *cells_;
  c.cells[c.distribution_cell[index]].distribution = -1;
  const int last = static_cast<int>(distributions_.size()) - 1;
  if (index != last) {
    distributions_[index] = distributions_[last];
    c.distribution_cell[index] = c.distribution_cell[last];
    c.cells[c.distribution_cell[index]].distribution = index;
  }
  distributions_.pop_back();
  c.distribution_cell.pop_back();
}

void VoxelMap::rebuild_distributions() {
  Cells& c = *cells_;
  for (const int slot : c.dirty_list) {
    Cells::Cell& cell = c.cells[slot];
    if (!cell.dirty) continue;  // dropped, or listed twice after its slot was reused
    cell.dirty = false;
    if (cell.moments.count < voxels_.min_points) continue;
    const Distribution distribution = cell.moments.to_distribution(voxels_.regularizer);
    if (cell.distribution >= 0) {
      distributions_[cell.distribution] = distribution;
    } else {
      cell.distribution = static_cast<int>(distributions_.size());
      distributions_.push_back(distribution);
      c.distribution_cell.push_back(slot);
    }
  }
  c.dirty_list.clear();
}

int VoxelMap::find(const VoxelIndex& index) const {
  const auto it = cells_->cell_of_key.find(pack_voxel(index));
  return it == cells_->cell_of_key.end() ? -1 : cells_->cells[it->second].distribution;
}

std::size_t VoxelMap::num_voxels() const {
  return cells_->cells.size() - cells_->free_slots.size();
}

}  // namespace litamin2

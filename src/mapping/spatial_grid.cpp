#include "litamin2/mapping/spatial_grid.hpp"

#include <algorithm>
#include <stdexcept>

namespace litamin2::mapping {

SpatialGrid::SpatialGrid(double cell_size) : cell_size_(cell_size) {
  if (!(cell_size > 0.0)) throw std::invalid_argument("SpatialGrid: cell size must be > 0");
}

void SpatialGrid::add(std::uint32_t node, const Eigen::Vector3d& position) {
  if (node != cell_of_.size()) throw std::logic_error("SpatialGrid: nodes must be added in order");
  const std::uint64_t k = key_of(position);
  cell_of_.push_back(k);
  cells_[k].push_back(node);
}

void SpatialGrid::move(std::uint32_t node, const Eigen::Vector3d& position) {
  const std::uint64_t k = key_of(position);
  std::uint64_t& current = cell_of_.at(node);
  if (k == current) return;
  std::vector<std::uint32_t>& old_cell = cells_[current];
  const auto it = std::lower_bound(old_cell.begin(), old_cell.end(), node);
  if (it != old_cell.end() && *it == node) old_cell.erase(it);
  if (old_cell.empty()) cells_.erase(current);
  current = k;
  std::vector<std::uint32_t>& new_cell = cells_[k];
  new_cell.insert(std::lower_bound(new_cell.begin(), new_cell.end(), node), node);
}

}  // namespace litamin2::mapping

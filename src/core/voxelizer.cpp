#include "litamin2/core/voxelizer.hpp"

#include "litamin2/core/voxel_key.hpp"
#include "litamin2/core/voxel_moments.hpp"

#include <tsl/robin_map.h>

namespace litamin2 {

struct Voxelizer::Table {
  tsl::robin_map<std::uint64_t, int, VoxelKeyHash> slot_of_key;
  std::vector<VoxelMoments> moments;
};

Voxelizer::Voxelizer(const VoxelizerConfig& config)
    : config_(config), table_(std::make_unique<Table>()) {}
Voxelizer::~Voxelizer() = default;
Voxelizer::Voxelizer(Voxelizer&&) noexcept = default;
Voxelizer& Voxelizer::operator=(Voxelizer&&) noexcept = default;

std::vector<Distribution> Voxelizer::voxelize(const PointCloud& scan) {
  const double size = config_.voxel_size;
  const double inv_size = 1.0 / size;
  const double min_range_sq = config_.min_range * config_.min_range;
  const double max_range_sq = config_.max_range * config_.max_range;
  Table& table = *table_;
  table.slot_of_key.clear();
  table.moments.clear();

  for (const Eigen::Vector3f& pf : scan.points) {
    const Eigen::Vector3d p = pf.cast<double>();
    const double range_sq = p.squaredNorm();
    if (!(range_sq >= min_range_sq && range_sq <= max_range_sq)) continue;  // also drops NaN
    const VoxelIndex index = voxel_index(p, inv_size);
    const auto [it, inserted] =
        table.slot_of_key.try_emplace(pack_voxel(index), static_cast<int>(table.moments.size()));
    if (inserted) {
      VoxelMoments& fresh = table.moments.emplace_back();
      fresh.origin = (index.cast<double>() + Eigen::Vector3d::Constant(0.5)) * size;
    }
    table.moments[it->second].add(p);
  }

  std::vector<Distribution> distributions;
  distributions.reserve(table.moments.size());
  for (const VoxelMoments& voxel : table.moments) {
    if (voxel.count >= config_.min_points) {
      distributions.push_back(voxel.to_distribution(config_.regularizer));
    }
  }
  return distributions;
}

}  // namespace litamin2

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

std::vector<Distribution> Voxelizer::voxelize(const PointCloud& scan,
                                              const Eigen::Isometry3d& grid_pose) {
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
    const Eigen::Vector3d g = grid_pose * p;
    const VoxelIndex index = voxel_index(g, inv_size);
    const auto [it, inserted] =
        table.slot_of_key.try_emplace(pack_voxel(index), static_cast<int>(table.moments.size()));
    if (inserted) {
      VoxelMoments& fresh = table.moments.emplace_back();
      fresh.origin = (index.cast<double>() + Eigen::Vector3d::Constant(0.5)) * size;
    }
    table.moments[it->second].add(g);
  }

  // Back to the sensor frame: p = G^-1 g, so mean' = G^-1 mean and C' = R^T C R.
  const Eigen::Isometry3d to_sensor = grid_pose.inverse();
  const Eigen::Matrix3d& r = to_sensor.linear();
  std::vector<Distribution> distributions;
  distributions.reserve(table.moments.size());
  for (const VoxelMoments& voxel : table.moments) {
    if (voxel.count < config_.min_points) continue;
    Distribution d = voxel.to_distribution(config_.regularizer);
    d.mean = to_sensor * d.mean;
    d.cov = r * d.cov * r.transpose();
    d.cov_inv = r * d.cov_inv * r.transpose();
    distributions.push_back(d);
  }
  return distributions;
}

}  // namespace litamin2

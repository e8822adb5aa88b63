#include "litamin2/core/voxelizer.hpp"

#include "litamin2/core/voxel_key.hpp"
#include "litamin2/core/voxel_moments.hpp"
#include "litamin2/core/voxel_voting.hpp"

#include <tsl/robin_map.h>

namespace litamin2 {

struct Voxelizer::Table {
  tsl::robin_map<std::uint64_t, int, VoxelKeyHash> slot_of_key;
};

Voxelizer::Voxelizer(const VoxelizerConfig& config)
    : config_(config), table_(std::make_unique<Table>()) {}
Voxelizer::~Voxelizer() = default;
Voxelizer::Voxelizer(Voxelizer&&) noexcept = default;
Voxelizer& Voxelizer::operator=(Voxelizer&&) noexcept = default;

std::vector<Distribution> Voxelizer::voxelize(const PointCloud& scan,
                                              const Eigen::Isometry3d& grid_pose) {
  Table& table = *table_;
  table.slot_of_key.clear();
  last_.grid_pose = grid_pose;
  last_.indices.clear();
  last_.moments.clear();
  vote_points(scan, grid_pose, config_, [&](const VoxelIndex& index) -> VoxelMoments& {
    const auto [it, inserted] =
        table.slot_of_key.try_emplace(pack_voxel(index), static_cast<int>(last_.moments.size()));
    if (inserted) {
      VoxelMoments& fresh = last_.moments.emplace_back();
      fresh.origin = (index.cast<double>() + Eigen::Vector3d::Constant(0.5)) * config_.voxel_size;
      last_.indices.push_back(index);
    }
    return last_.moments[it->second];
  });

  // Back to the sensor frame: p = G^-1 g, so mean' = G^-1 mean and C' = R^T C R.
  const Eigen::Isometry3d to_sensor = grid_pose.inverse();
  const Eigen::Matrix3d& r = to_sensor.linear();
  std::vector<Distribution> distributions;
  distributions.reserve(last_.moments.size());
  for (const VoxelMoments& voxel : last_.moments) {
    if (voxel.count < config_.min_points) continue;
    Distribution d = voxel.to_distribution(config_.regularizer);
    d.mean = to_sensor * d.mean;
    d.cov = r * d.cov * r.transpose();
    d.shape_cov = r * d.shape_cov * r.transpose();
    d.shape_cov_inv = r * d.shape_cov_inv * r.transpose();
    distributions.push_back(d);
  }
  return distributions;
}

}  // namespace litamin2

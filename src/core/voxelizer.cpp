#include "litamin2/core/voxelizer.hpp"

#include "litamin2/core/voxel_key.hpp"
#include "litamin2/core/voxel_moments.hpp"
#include "litamin2/core/voxel_voting.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tsl/robin_map.h>

namespace litamin2 {
namespace {

/// Points per chunk. Fixed, so the result does not depend on the number of threads.
constexpr std::size_t kChunkPoints = 16384;

using SlotOfKey = tsl::robin_map<std::uint64_t, int, VoxelKeyHash>;

/// Adds moments to the voxel of `index` in (slots, out), creating it in first-seen order.
VoxelMoments& moments_of(SlotOfKey& slots, GridVoxels& out, const VoxelIndex& index,
                         double voxel_size) {
  const auto [it, inserted] =
      slots.try_emplace(pack_voxel(index), static_cast<int>(out.moments.size()));
  if (inserted) {
    VoxelMoments& fresh = out.moments.emplace_back();
    fresh.origin = (index.cast<double>() + Eigen::Vector3d::Constant(0.5)) * voxel_size;
    out.indices.push_back(index);
  }
  return out.moments[it->second];
}

}  // namespace

/// One table per chunk of points (voted in parallel) and the merged table.
struct Voxelizer::Table {
  struct Chunk {
    SlotOfKey slots;
    GridVoxels voxels;
  };
  std::vector<Chunk> chunks;
  SlotOfKey slots;
};

Voxelizer::Voxelizer(const VoxelizerConfig& config)
    : config_(config), table_(std::make_unique<Table>()) {}
Voxelizer::~Voxelizer() = default;
Voxelizer::Voxelizer(Voxelizer&&) noexcept = default;
Voxelizer& Voxelizer::operator=(Voxelizer&&) noexcept = default;

std::vector<Distribution> Voxelizer::voxelize(const PointCloud& scan,
                                              const Eigen::Isometry3d& grid_pose) {
  Table& table = *table_;
  const double size = config_.voxel_size;
  // Chunks are voted in parallel, each into its own table, then merged in chunk order: the
  // sums, and the order of the voxels, are the same whatever the thread count.
  const std::size_t num_chunks =
      std::max<std::size_t>(1, (scan.points.size() + kChunkPoints - 1) / kChunkPoints);
  if (table.chunks.size() < num_chunks) table.chunks.resize(num_chunks);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, num_chunks, 1),
      [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t c = range.begin(); c != range.end(); ++c) {
          Table::Chunk& chunk = table.chunks[c];
          chunk.slots.clear();
          chunk.voxels.indices.clear();
          chunk.voxels.moments.clear();
          const std::size_t first = c * kChunkPoints;
          const std::size_t last = std::min(scan.points.size(), first + kChunkPoints);
          const Eigen::Vector3f* data = scan.points.data();
          vote_points(data + first, data + last, grid_pose, config_,
                      [&](const VoxelIndex& index) -> VoxelMoments& {
                        return moments_of(chunk.slots, chunk.voxels, index, size);
                      });
        }
      },
      tbb::simple_partitioner());

  table.slots.clear();
  last_.grid_pose = grid_pose;
  last_.indices.clear();
  last_.moments.clear();
  for (std::size_t c = 0; c < num_chunks; ++c) {
    const GridVoxels& part = table.chunks[c].voxels;
    for (std::size_t i = 0; i < part.moments.size(); ++i) {
      moments_of(table.slots, last_, part.indices[i], size).merge(part.moments[i]);
    }
  }

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

#include "litamin2/core/correspondence_search.hpp"

namespace litamin2 {
namespace {

/// Looks at the query's voxel and its 26 neighbours: exact for radii up to one voxel edge.
class VoxelNeighborSearch final : public CorrespondenceSearch {
 public:
  explicit VoxelNeighborSearch(const VoxelMap& map)
      : map_(map), inv_size_(1.0 / map.voxel_size()) {}

  int nearest(const Eigen::Vector3d& query, double max_distance_sq) const override {
    const VoxelIndex center = voxel_index(query, inv_size_);
    const auto& distributions = map_.distributions();
    int best = -1;
    double best_sq = max_distance_sq;
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dz = -1; dz <= 1; ++dz) {
          const int index = map_.find(center + VoxelIndex(dx, dy, dz));
          if (index < 0) continue;
          const double distance_sq = (distributions[index].mean - query).squaredNorm();
          if (distance_sq < best_sq) {
            best_sq = distance_sq;
            best = index;
          }
        }
      }
    }
    return best;
  }

 private:
  const VoxelMap& map_;
  double inv_size_;
};

}  // namespace

std::unique_ptr<CorrespondenceSearch> make_voxel_neighbor_search(const VoxelMap& map) {
  return std::make_unique<VoxelNeighborSearch>(map);
}

}  // namespace litamin2

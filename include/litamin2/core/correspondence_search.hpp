#pragma once
/// Nearest map distribution of a query point (paper Sec. III-B: the nearest distribution by
/// mean, found with a kd-tree). Two implementations that return the same answer whenever the
/// search radius is at most one voxel: a kd-tree (KdTreeSearch) and a lookup of the 27 voxels
/// around the query (VoxelNeighborSearch). docs/benchmarks.md compares their speed.

#include "litamin2/core/voxel_map.hpp"

#include <Eigen/Core>
#include <memory>

namespace litamin2 {

enum class CorrespondenceMethod { Voxel27, KdTree };

class CorrespondenceSearch {
 public:
  virtual ~CorrespondenceSearch() = default;
  /// Index into map.distributions() of the nearest mean within sqrt(max_distance_sq) of
  /// `query`, or -1.
  virtual int nearest(const Eigen::Vector3d& query, double max_distance_sq) const = 0;
};

/// Builds the search of the given kind over the map's current distributions. The map must
/// outlive the search and not change while it is used.
std::unique_ptr<CorrespondenceSearch> make_correspondence_search(CorrespondenceMethod method,
                                                                 const VoxelMap& map);

}  // namespace litamin2

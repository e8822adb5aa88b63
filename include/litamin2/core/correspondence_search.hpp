#pragma once
/// Nearest map distribution of a query point (paper Sec. III-B: the nearest distribution by
/// mean, found with a kd-tree). Two implementations that return the same answer whenever the
/// search radius is at most one voxel: a kd-tree (KdTreeSearch) and a lookup of the 27 voxels
/// around the query (VoxelNeighborSearch). docs/benchmarks.md compares their speed.

#include "litamin2/core/voxel_map.hpp"

#include <Eigen/Core>
#include <memory>

namespace litamin2 {

enum class CorrespondenceMethod { kVoxel27, kKdTree };

/// The two map means nearest to a query, for reusing a search when the query moves
/// (NearestCache).
struct NearestTwo {
  /// Index into map.distributions() of the nearest mean (whatever its distance), or -1.
  int index = -1;
  /// Squared distance to it.
  double distance_sq = 0.0;
  /// Distance to the second nearest mean; infinite when there is none.
  double second_distance = 0.0;
};

class CorrespondenceSearch {
 public:
  virtual ~CorrespondenceSearch() = default;
  /// Index into map.distributions() of the nearest mean within sqrt(max_distance_sq) of
  /// `query`, or -1.
  virtual int nearest(const Eigen::Vector3d& query, double max_distance_sq) const = 0;
  /// The nearest and second nearest means, without a distance limit, where the search supports
  /// it (false otherwise). For any query, `nearest(query, d2)` is `nearest_two(query).index`
  /// if its distance_sq < d2, else -1.
  virtual bool nearest_two(const Eigen::Vector3d& /*query*/, NearestTwo& /*out*/) const {
    return false;
  }
};

/// Builds the search of the given kind over the map's current distributions. The map must
/// outlive the search and not change while it is used.
std::unique_ptr<CorrespondenceSearch> make_correspondence_search(CorrespondenceMethod method,
                                                                 const VoxelMap& map);

}  // namespace litamin2

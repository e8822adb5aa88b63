#include "litamin2/core/correspondence_search.hpp"

namespace litamin2 {

std::unique_ptr<CorrespondenceSearch> make_voxel_neighbor_search(const VoxelMap& map);
std::unique_ptr<CorrespondenceSearch> make_kdtree_search(const VoxelMap& map);

std::unique_ptr<CorrespondenceSearch> make_correspondence_search(CorrespondenceMethod method,
                                                                 const VoxelMap& map) {
  return method == CorrespondenceMethod::kKdTree ? make_kdtree_search(map)
                                                 : make_voxel_neighbor_search(map);
}

}  // namespace litamin2

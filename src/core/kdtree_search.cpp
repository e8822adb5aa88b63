#include "litamin2/core/correspondence_search.hpp"

#include <nanoflann.hpp>

#include <cmath>
#include <limits>

namespace litamin2 {
namespace {

/// nanoflann's view of the map's distribution means.
struct MeanCloud {
  const std::vector<Distribution>& distributions;
  std::size_t kdtree_get_point_count() const { return distributions.size(); }
  double kdtree_get_pt(std::size_t index, std::size_t dim) const {
    return distributions[index].mean(static_cast<int>(dim));
  }
  template <class BoundingBox>
  bool kdtree_get_bbox(BoundingBox&) const {
    return false;
  }
};

/// The paper's kd-tree over distribution means.
class KdTreeSearch final : public CorrespondenceSearch {
  using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, MeanCloud>,
                                                   MeanCloud, 3, int>;

 public:
  explicit KdTreeSearch(const VoxelMap& map)
      : cloud_{map.distributions()},
        tree_(3, cloud_, nanoflann::KDTreeSingleIndexAdaptorParams(10)) {
    tree_.buildIndex();
  }

  int nearest(const Eigen::Vector3d& query, double max_distance_sq) const override {
    if (cloud_.distributions.empty()) return -1;
    int index = -1;
    double distance_sq = 0.0;
    nanoflann::KNNResultSet<double, int> result(1);
    result.init(&index, &distance_sq);
    tree_.findNeighbors(result, query.data(), nanoflann::SearchParams());
    return (index >= 0 && distance_sq < max_distance_sq) ? index : -1;
  }

  bool nearest_two(const Eigen::Vector3d& query, NearestTwo& out) const override {
    int indices[2] = {-1, -1};
    double distances_sq[2] = {0.0, 0.0};
    out = NearestTwo();
    out.second_distance = std::numeric_limits<double>::infinity();
    if (cloud_.distributions.empty()) return true;
    nanoflann::KNNResultSet<double, int> result(2);
    result.init(indices, distances_sq);
    tree_.findNeighbors(result, query.data(), nanoflann::SearchParams());
    out.index = indices[0];
    out.distance_sq = distances_sq[0];
    if (result.size() > 1) out.second_distance = std::sqrt(distances_sq[1]);
    return true;
  }

 private:
  MeanCloud cloud_;
  Tree tree_;
};

}  // namespace

std::unique_ptr<CorrespondenceSearch> make_kdtree_search(const VoxelMap& map) {
  return std::make_unique<KdTreeSearch>(map);
}

}  // namespace litamin2

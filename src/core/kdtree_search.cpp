#include "litamin2/core/correspondence_search.hpp"
#include "litamin2/core/mean_kdtree.hpp"

#include <cmath>
#include <limits>

namespace litamin2 {
namespace {

std::vector<Eigen::Vector3d> means_of(const std::vector<Distribution>& distributions) {
  std::vector<Eigen::Vector3d> means;
  means.reserve(distributions.size());
  for (const Distribution& distribution : distributions) means.push_back(distribution.mean);
  return means;
}

/// The paper's kd-tree over distribution means.
class KdTreeSearch final : public CorrespondenceSearch {
 public:
  explicit KdTreeSearch(const VoxelMap& map) : tree_(means_of(map.distributions())) {}

  int nearest(const Eigen::Vector3d& query, double max_distance_sq) const override {
    double distance_sq = 0.0;
    return tree_.nearest(query, max_distance_sq, distance_sq);
  }

  bool nearest_two(const Eigen::Vector3d& query, NearestTwo& out) const override {
    int indices[2];
    double distances_sq[2];
    tree_.nearest_two(query, indices, distances_sq);
    out = NearestTwo();
    out.index = indices[0];
    out.distance_sq = indices[0] >= 0 ? distances_sq[0] : 0.0;
    out.second_distance =
        indices[1] >= 0 ? std::sqrt(distances_sq[1]) : std::numeric_limits<double>::infinity();
    return true;
  }

 private:
  MeanKdTree tree_;
};

}  // namespace

std::unique_ptr<CorrespondenceSearch> make_kdtree_search(const VoxelMap& map) {
  return std::make_unique<KdTreeSearch>(map);
}

}  // namespace litamin2

#pragma once
/// A static kd-tree over 3D points for exact nearest and second-nearest queries: the map
/// means' index behind KdTreeSearch (correspondence_search.hpp). Built once per keyframe, so
/// its build is on the tracker's path: per node, one bounding-box pass and one branch-free
/// partition at the midpoint of the widest side (the median, by nth_element, only where the
/// midpoint would leave under 1/8 of the points on one side); points are copied in tree order
/// (a leaf's points are contiguous). Distances are squared_distance_xyz, as NearestCache's
/// reuse test computes them.

#include <Eigen/Core>

#include <vector>

namespace litamin2 {

/// Squared distance summed in x, y, z order: the metric of MeanKdTree, and of NearestCache's
/// reuse test, which must meet the distance limit exactly when a fresh search would.
inline double squared_distance_xyz(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  double sum = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double d = a(i) - b(i);
    sum += d * d;
  }
  return sum;
}

class MeanKdTree {
 public:
  /// Builds the tree over `points` (copied); the answers' indices are into `points`.
  explicit MeanKdTree(const std::vector<Eigen::Vector3d>& points);

  /// Index of the nearest point whose squared distance to `query` is below `max_distance_sq`,
  /// or -1; its squared distance in `distance_sq` when found.
  int nearest(const Eigen::Vector3d& query, double max_distance_sq, double& distance_sq) const;
  /// The nearest and second-nearest points, without a distance limit: indices (-1 where
  /// there are fewer points) and squared distances (infinite where there is none).
  void nearest_two(const Eigen::Vector3d& query, int indices[2], double distances_sq[2]) const;
  std::size_t size() const { return points_.size(); }

 private:
  struct Node {
    int begin = 0, end = 0;     // points_[begin, end) below this node
    int left = -1, right = -1;  // children, -1 for a leaf
    int dim = 0;                // split dimension
    double split = 0.0;         // left: coordinate <= split; right: >= split
  };
  template <int count>
  struct Best;
  int build(std::vector<int>& order, const std::vector<Eigen::Vector3d>& points, int begin, int end,
            int depth);
  template <int count>
  void search(const Eigen::Vector3d& query, Best<count>& best) const;

  std::vector<Node> nodes_;
  std::vector<Eigen::Vector3d> points_;  // in tree order
  std::vector<int> index_;               // points_[k] is the input's point index_[k]
};

}  // namespace litamin2

#include "litamin2/core/mean_kdtree.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <stdexcept>

namespace litamin2 {
namespace {

/// Points per leaf at most.
constexpr int kLeafSize = 10;

/// Levels below the root at most. A split leaves at least 1/8 of a node's points on each side
/// (the midpoint) or halves them (the median), so a node at depth d holds at most (7/8)^d of
/// the n points, and only nodes of more than kLeafSize points split: d <= 1 + ln(n / 11) /
/// ln(8 / 7), which is 144 for n = 2^31. The search's stack of far branches holds one entry a
/// level.
constexpr int kMaxDepth = 160;

}  // namespace

/// The `count` (1 or 2) best points so far; a point replaces one only when strictly nearer.
/// The count is a template argument: the leaf scan's tests on it are decided at compile time.
template <int count>
struct MeanKdTree::Best {
  static_assert(count == 1 || count == 2);
  int indices[2] = {-1, -1};
  double distances_sq[2];
  explicit Best(double bound) {
    distances_sq[0] = count == 1 ? bound : std::numeric_limits<double>::infinity();
    distances_sq[1] = count == 2 ? bound : std::numeric_limits<double>::infinity();
  }
  /// The distance a point must beat to enter.
  double worst() const { return distances_sq[count - 1]; }
  void add(double distance_sq, int index) {
    if (!(distance_sq < worst())) return;
    if (count == 2 && distance_sq < distances_sq[0]) {
      distances_sq[1] = distances_sq[0];
      indices[1] = indices[0];
      distances_sq[0] = distance_sq;
      indices[0] = index;
    } else {
      distances_sq[count - 1] = distance_sq;
      indices[count - 1] = index;
    }
  }
};

MeanKdTree::MeanKdTree(const std::vector<Eigen::Vector3d>& points) {
  const int n = static_cast<int>(points.size());
  std::vector<int> order(points.size());
  for (int i = 0; i < n; ++i) order[i] = i;
  nodes_.reserve(2 * static_cast<std::size_t>(n / kLeafSize + 1));
  if (n > 0) build(order, points, 0, n, 0);
  points_.reserve(points.size());
  for (const int i : order) points_.push_back(points[i]);
  index_ = std::move(order);
}

int MeanKdTree::build(std::vector<int>& order, const std::vector<Eigen::Vector3d>& points,
                      int begin, int end, int depth) {
  if (depth > kMaxDepth) throw std::logic_error("MeanKdTree: deeper than its bound");
  const int id = static_cast<int>(nodes_.size());
  nodes_.push_back(Node{begin, end});
  if (end - begin <= kLeafSize) return id;
  Eigen::Vector3d lo = points[order[begin]], hi = lo;
  for (int k = begin + 1; k < end; ++k) {
    lo = lo.cwiseMin(points[order[k]]);
    hi = hi.cwiseMax(points[order[k]]);
  }
  int dim = 0;
  const double extent = (hi - lo).maxCoeff(&dim);
  if (!(extent > 0.0)) return id;  // all points equal: one leaf
  // The midpoint of the widest side splits without a selection: one branch-free pass puts the
  // points below it first. Both sides hold a point (the extremes), so the recursion ends.
  double split = 0.5 * (lo(dim) + hi(dim));
  int mid = begin;
  for (int k = begin; k < end; ++k) {
    const int point = order[k];
    const int other = order[mid];
    const bool below = points[point](dim) < split;
    order[k] = below ? other : point;
    order[mid] = below ? point : other;
    mid += below;
  }
  // A lopsided split (clustered points) falls back to the median, which bounds the depth.
  const int size = end - begin;
  if (8 * std::min(mid - begin, end - mid) < size) {
    mid = begin + size / 2;
    std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end,
                     [&](int a, int b) { return points[a](dim) < points[b](dim); });
    split = points[order[mid]](dim);
  }
  const int left = build(order, points, begin, mid, depth + 1);
  const int right = build(order, points, mid, end, depth + 1);
  Node& node = nodes_[id];
  node.left = left;
  node.right = right;
  node.dim = dim;
  node.split = split;
  return id;
}

template <int count>
void MeanKdTree::search(const Eigen::Vector3d& query, Best<count>& best) const {
  // Depth first, nearer child first, as a recursion would visit the nodes, with the farther
  // children on a stack: a far child is entered only if the distance to its side of the split
  // is still below the worst kept distance once everything pushed after it is done.
  struct FarBranch {
    int node;
    double distance_sq;  // along the split dimension: a lower bound on its points' distance
  };
  std::array<FarBranch, kMaxDepth + 1> pending;
  int top = 0;
  int node_id = 0;
  for (;;) {
    const Node& node = nodes_[node_id];
    if (node.left >= 0) {
      const double diff = query(node.dim) - node.split;
      pending[top++] = {diff < 0.0 ? node.right : node.left, diff * diff};
      node_id = diff < 0.0 ? node.left : node.right;
      continue;
    }
    for (int k = node.begin; k < node.end; ++k) {
      best.add(squared_distance_xyz(query, points_[k]), k);
    }
    do {
      if (top == 0) return;
      --top;
    } while (!(pending[top].distance_sq < best.worst()));
    node_id = pending[top].node;
  }
}

int MeanKdTree::nearest(const Eigen::Vector3d& query, double max_distance_sq,
                        double& distance_sq) const {
  if (nodes_.empty()) return -1;
  Best<1> best(max_distance_sq);
  search(query, best);
  if (best.indices[0] < 0) return -1;
  distance_sq = best.distances_sq[0];
  return index_[best.indices[0]];
}

void MeanKdTree::nearest_two(const Eigen::Vector3d& query, int indices[2],
                             double distances_sq[2]) const {
  Best<2> best(std::numeric_limits<double>::infinity());
  if (!nodes_.empty()) search(query, best);
  for (int i = 0; i < 2; ++i) {
    indices[i] = best.indices[i] < 0 ? -1 : index_[best.indices[i]];
    distances_sq[i] = best.distances_sq[i];
  }
}

}  // namespace litamin2

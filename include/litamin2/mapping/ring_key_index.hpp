#pragma once
/// The place descriptors' ring keys in a kd-tree (nanoflann's dynamic index: a logarithmic
/// set of static trees, so an insertion costs O(log N) amortised and a query O(log^2 N)), for
/// the descriptor search's shortlist: the k eligible keyframes whose ring keys are nearest to
/// the query's. The result is exactly the linear scan's (the k smallest squared Euclidean
/// distances computed in double as ring_key_distance does, ties broken by the caller's order).

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

namespace litamin2::mapping {

class RingKeyIndex {
 public:
  /// Dimension of the ring keys (the descriptor's rings).
  explicit RingKeyIndex(int dimensions);
  ~RingKeyIndex();
  RingKeyIndex(RingKeyIndex&&) noexcept;
  RingKeyIndex& operator=(RingKeyIndex&&) noexcept;

  /// Adds the ring key of node `size()` (nodes are numbered in the order they are added).
  void add(const std::vector<float>& ring_key);
  std::size_t size() const;

  /// Up to k nodes with eligible(node), nearest to `ring_key`, ordered by (distance, before).
  std::vector<std::uint32_t> nearest(
      const std::vector<float>& ring_key, std::size_t k,
      const std::function<bool(std::uint32_t)>& eligible,
      const std::function<bool(std::uint32_t, std::uint32_t)>& before) const;

  /// The squared distance between `ring_key` and node's, as ring_key_distance computes it.
  double distance(const std::vector<float>& ring_key, std::uint32_t node) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace litamin2::mapping

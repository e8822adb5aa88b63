#pragma once
/// Reuses nearest-neighbour searches across the Newton iterations of one registration.
///
/// Between iterations a source mean moves by a few centimetres while the map's means are metres
/// apart, so its nearest map mean rarely changes. With d1 and d2 the distances from the query q0
/// of the last search to its nearest and second nearest means, a query q with |q - q0| = delta
/// has the same nearest mean whenever 2 delta < d2 - d1: every other mean is at least
/// d2 - delta > d1 + delta away, and the old nearest at most d1 + delta (triangle inequality).
/// The answer is then the search's own, without searching; otherwise the search runs again.

#include "litamin2/core/correspondence_search.hpp"
#include "litamin2/core/distribution.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace litamin2 {

class NearestCache {
 public:
  /// A cache for `slots` queries (one per source distribution) against `search`, whose map
  /// means are `targets`. Both must outlive the cache and not change.
  NearestCache(const CorrespondenceSearch& search, const std::vector<Distribution>& targets,
               std::size_t slots);

  /// What `search.nearest(query, max_distance_sq)` returns, reusing the last search of `slot`
  /// when the triangle inequality allows. Different slots may be used from different threads.
  int nearest(std::size_t slot, const Eigen::Vector3d& query, double max_distance_sq);

  /// Queries answered without a search / with one, over the cache's life (for statistics; not
  /// thread-safe, read after the parallel work).
  std::size_t reused() const;
  std::size_t searched() const;

 private:
  struct Entry {
    Eigen::Vector3d query = Eigen::Vector3d::Zero();
    NearestTwo found;
    bool valid = false;
    std::size_t reused = 0;
    std::size_t searched = 0;
  };
  const CorrespondenceSearch& search_;
  const std::vector<Distribution>& targets_;
  std::vector<Entry> entries_;
};

}  // namespace litamin2

#include "litamin2/core/nearest_cache.hpp"

#include "litamin2/core/mean_kdtree.hpp"

#include <cmath>

namespace litamin2 {
namespace {

/// Margin on the reuse test so that rounding in the distances can never decide it.
constexpr double kMargin = 1e-9;

}  // namespace

NearestCache::NearestCache(const CorrespondenceSearch& search,
                           const std::vector<Distribution>& targets, std::size_t slots)
    : search_(search), targets_(targets), entries_(slots) {}

int NearestCache::nearest(std::size_t slot, const Eigen::Vector3d& query, double max_distance_sq) {
  Entry& entry = entries_[slot];
  if (entry.valid && entry.found.index >= 0) {
    const double moved = (query - entry.query).norm();
    if (2.0 * moved + kMargin < entry.found.second_distance - std::sqrt(entry.found.distance_sq)) {
      ++entry.reused;
      const int index = entry.found.index;
      return squared_distance_xyz(query, targets_[index].mean) < max_distance_sq ? index : -1;
    }
  }
  ++entry.searched;
  if (!search_.nearest_two(query, entry.found)) {
    entry.valid = false;
    return search_.nearest(query, max_distance_sq);
  }
  entry.query = query;
  entry.valid = true;
  const int index = entry.found.index;
  return (index >= 0 && entry.found.distance_sq < max_distance_sq) ? index : -1;
}

std::size_t NearestCache::reused() const {
  std::size_t total = 0;
  for (const Entry& entry : entries_) total += entry.reused;
  return total;
}

std::size_t NearestCache::searched() const {
  std::size_t total = 0;
  for (const Entry& entry : entries_) total += entry.searched;
  return total;
}

}  // namespace litamin2

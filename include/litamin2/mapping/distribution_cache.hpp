#pragma once
/// The keyframes' distributions as the mapper reads them (verification, submaps, map tiles):
/// a least-recently-used cache bounded in bytes in front of a loader (the aggregator's store).
/// Without a loader nothing can be re-read, so nothing is evicted: the offline tool and tests
/// keep every keyframe's distributions in memory, as before.
///
/// Entries are shared: a caller holding one keeps it alive after it is evicted, so a
/// verification never sees its submap disappear. Not thread-safe (the mapping thread's).

#include "litamin2/core/distribution.hpp"
#include "litamin2/core/keyframe.hpp"

#include <cstddef>
#include <functional>
#include <list>
#include <map>
#include <memory>
#include <vector>

namespace litamin2::mapping {

using Distributions = std::shared_ptr<const std::vector<Distribution>>;

struct DistributionCacheStats {
  std::size_t hits = 0;
  std::size_t misses = 0;
  std::size_t evictions = 0;
  std::size_t entries = 0;
  std::size_t bytes = 0;
  /// CPU time of the calling thread in the loader (misses), seconds.
  double load_s = 0.0;
};

class DistributionCache {
 public:
  /// Reads a keyframe's distributions (throws if it cannot).
  using Loader = std::function<std::vector<Distribution>(const KeyframeKey&)>;

  /// No loader: unbounded, every entry kept. With one: at most max_bytes of distributions
  /// (at least the latest entry).
  explicit DistributionCache(Loader loader = {}, std::size_t max_bytes = 0);

  /// The keyframe's distributions: from the cache, else from the loader (then cached).
  /// Throws std::out_of_range for a key neither holds.
  Distributions get(const KeyframeKey& key);
  /// Caches a keyframe's distributions (a new keyframe: it is about to be used).
  void put(const KeyframeKey& key, std::vector<Distribution> distributions);

  DistributionCacheStats stats() const;
  bool bounded() const { return static_cast<bool>(loader_); }
  static std::size_t bytes_of(const std::vector<Distribution>& d);

 private:
  void insert(const KeyframeKey& key, Distributions d);
  void evict();

  Loader loader_;
  std::size_t max_bytes_;
  /// Most recently used first.
  std::list<std::pair<KeyframeKey, Distributions>> lru_;
  std::map<KeyframeKey, decltype(lru_)::iterator> index_;
  DistributionCacheStats stats_;
};

}  // namespace litamin2::mapping

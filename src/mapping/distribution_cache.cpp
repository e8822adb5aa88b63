#include "litamin2/mapping/distribution_cache.hpp"

#include "litamin2/core/stopwatch.hpp"

#include <stdexcept>

namespace litamin2::mapping {

DistributionCache::DistributionCache(Loader loader, std::size_t max_bytes)
    : loader_(std::move(loader)), max_bytes_(max_bytes) {}

std::size_t DistributionCache::bytes_of(const std::vector<Distribution>& d) {
  return d.capacity() * sizeof(Distribution) + sizeof(d);
}

Distributions DistributionCache::get(const KeyframeKey& key) {
  const auto it = index_.find(key);
  if (it != index_.end()) {
    ++stats_.hits;
    lru_.splice(lru_.begin(), lru_, it->second);
    return it->second->second;
  }
  if (!loader_) {
    throw std::out_of_range("distribution cache: no distributions of keyframe '" + key.stream +
                            "'/" + std::to_string(key.id));
  }
  ++stats_.misses;
  const double t = thread_cpu_seconds();
  auto d = std::make_shared<const std::vector<Distribution>>(loader_(key));
  stats_.load_s += thread_cpu_seconds() - t;
  insert(key, d);
  return d;
}

void DistributionCache::put(const KeyframeKey& key, std::vector<Distribution> distributions) {
  const auto it = index_.find(key);
  if (it != index_.end()) {
    stats_.bytes -= bytes_of(*it->second->second);
    lru_.erase(it->second);
    index_.erase(it);
  }
  insert(key, std::make_shared<const std::vector<Distribution>>(std::move(distributions)));
}

void DistributionCache::insert(const KeyframeKey& key, Distributions d) {
  stats_.bytes += bytes_of(*d);
  lru_.emplace_front(key, std::move(d));
  index_[key] = lru_.begin();
  evict();
  stats_.entries = lru_.size();
}

void DistributionCache::evict() {
  if (!loader_ || max_bytes_ == 0) return;
  while (stats_.bytes > max_bytes_ && lru_.size() > 1) {
    stats_.bytes -= bytes_of(*lru_.back().second);
    index_.erase(lru_.back().first);
    lru_.pop_back();
    ++stats_.evictions;
  }
}

DistributionCacheStats DistributionCache::stats() const {
  return stats_;
}

}  // namespace litamin2::mapping

#include "litamin2/aggregator/tile_rate_limiter.hpp"

#include <stdexcept>

namespace litamin2::aggregator {

TileRateLimiter::TileRateLimiter(Clock::duration period) : period_(period) {
  if (period < Clock::duration::zero())
    throw std::invalid_argument("TileRateLimiter: negative period");
}

bool TileRateLimiter::offer(mapping::TileKey key, Clock::time_point now) {
  if (deferred_.count(key)) {
    ++deferred_count_;
    ++folded_count_;
    return false;
  }
  const auto it = last_sent_.find(key);
  if (it != last_sent_.end() && now - it->second < period_) {
    deferred_.insert(key);
    ++deferred_count_;
    return false;
  }
  last_sent_[key] = now;
  return true;
}

std::vector<mapping::TileKey> TileRateLimiter::take_due(Clock::time_point now) {
  std::vector<mapping::TileKey> due;
  for (auto it = deferred_.begin(); it != deferred_.end();) {
    const auto sent = last_sent_.find(*it);
    if (sent == last_sent_.end() || now - sent->second >= period_) {
      due.push_back(*it);
      last_sent_[*it] = now;
      it = deferred_.erase(it);
    } else {
      ++it;
    }
  }
  forget_old(now);
  return due;
}

std::vector<mapping::TileKey> TileRateLimiter::take_all(Clock::time_point now) {
  std::vector<mapping::TileKey> all(deferred_.begin(), deferred_.end());
  for (const mapping::TileKey& key : all) last_sent_[key] = now;
  deferred_.clear();
  return all;
}

void TileRateLimiter::forget_old(Clock::time_point now) {
  // A tile sent a period ago or more goes out at its next change: its entry is not needed.
  for (auto it = last_sent_.begin(); it != last_sent_.end();) {
    if (now - it->second >= period_ && !deferred_.count(it->first))
      it = last_sent_.erase(it);
    else
      ++it;
  }
}

}  // namespace litamin2::aggregator

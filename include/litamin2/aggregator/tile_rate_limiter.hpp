#pragma once
/// Which changed map tiles go out now and which wait: each tile goes out at most once per
/// period. A change of a tile that went out less than a period ago is deferred until the period
/// has passed; further changes meanwhile are folded into the one deferred (the caller keeps
/// only the newest contents), so a tile changed several times within a period goes out once,
/// with its newest revision. Holds one entry per tile sent within the last period and one per
/// deferred tile. No clock of its own, no threads, no transport: the DDS node's MapTilePublisher
/// drives it.

#include "litamin2/mapping/map_tile.hpp"

#include <chrono>
#include <cstdint>
#include <map>
#include <set>
#include <vector>

namespace litamin2::aggregator {

class TileRateLimiter {
 public:
  using Clock = std::chrono::steady_clock;

  /// `period` >= 0 (0: every change goes out at once).
  explicit TileRateLimiter(Clock::duration period);

  /// Tile `key` changed at `now`. True: send it now (recorded as sent at `now`). False: it is
  /// deferred (take_due returns it once its period has passed).
  bool offer(mapping::TileKey key, Clock::time_point now);
  /// The deferred tiles whose period has passed at `now`, by key, recorded as sent at `now`.
  std::vector<mapping::TileKey> take_due(Clock::time_point now);
  /// Every deferred tile, by key, recorded as sent at `now` (at shutdown).
  std::vector<mapping::TileKey> take_all(Clock::time_point now);

  std::size_t deferred_now() const { return deferred_.size(); }
  /// Offers deferred, and those of them folded into a tile already deferred.
  std::uint64_t deferred() const { return deferred_count_; }
  std::uint64_t folded() const { return folded_count_; }

 private:
  void forget_old(Clock::time_point now);

  Clock::duration period_;
  std::map<mapping::TileKey, Clock::time_point> last_sent_;
  std::set<mapping::TileKey> deferred_;
  std::uint64_t deferred_count_ = 0;
  std::uint64_t folded_count_ = 0;
};

}  // namespace litamin2::aggregator

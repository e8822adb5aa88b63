#pragma once
/// The aggregator's writer of rt/litamin2/map_tiles: each changed tile the mapping thread hands
/// over (offer) becomes a litamin2/msg/MapTile with the next revision, written at once or, when
/// the tile went out less than map_tiles.publish_period_s ago, held (the newest contents and
/// revision only) and written by flush_due from the node's thread once its period has passed
/// (TileRateLimiter). flush_all at shutdown writes every held tile: none is lost at a clean
/// stop; at a kill the held ones (at most a period's changes) are lost to the wire, not to the
/// store, and go out again at the next start (every tile is published once at start).
///
/// Revisions follow the wall clock: each is the wall clock's microseconds since the epoch, or
/// the previous revision + 1 if that is larger. A tile's revision increases with each change
/// published, also across restarts while the wall clock does not go back; and the revisions of
/// two aggregators (a hot standby, standby.strength) are comparable by when they were
/// published, so a client keeping the highest revision per tile takes the standby's tiles
/// after a switch even if the standby started first (with clocks in sync to well under a
/// publish period).

#include "litamin2/aggregator/aggregator_outputs.hpp"
#include "litamin2/aggregator/tile_rate_limiter.hpp"
#include "litamin2/msg/MapTile.h"

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>

namespace litamin2::aggregator {

struct MapTileCounters {
  /// Samples written, and writes that failed.
  std::uint64_t published = 0;
  std::uint64_t write_failures = 0;
  /// Changes held back by the period (folded: into a tile already held).
  std::uint64_t deferred = 0;
  std::uint64_t folded = 0;
  /// Tiles held now.
  std::size_t held = 0;
};

class MapTilePublisher {
 public:
  using Clock = std::chrono::steady_clock;

  /// Writes one sample (the DataWriter's write; a recorder in tests); false: failed.
  using Write = std::function<bool(litamin2::msg::MapTile&)>;
  /// The wall clock in microseconds since the epoch (a fixed or stepped clock in tests).
  using RevisionClock = std::function<std::uint64_t()>;

  MapTilePublisher(Write write, double period_s, RevisionClock revision_clock);

  /// The mapping thread: `tile` changed.
  void offer(const TileOutput& tile, Clock::time_point now = Clock::now());
  /// The node's thread: writes the held tiles whose period has passed.
  void flush_due(Clock::time_point now = Clock::now());
  /// Writes every held tile.
  void flush_all();

  MapTileCounters counters() const;

 private:
  void write(litamin2::msg::MapTile& msg);

  Write write_;
  mutable std::mutex mutex_;
  TileRateLimiter limiter_;
  std::map<mapping::TileKey, litamin2::msg::MapTile> held_;
  RevisionClock revision_clock_;
  /// The last revision given, 0 before the first.
  std::uint64_t last_revision_ = 0;
  std::uint64_t published_ = 0;
  std::uint64_t write_failures_ = 0;
};

}  // namespace litamin2::aggregator

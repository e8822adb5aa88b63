#pragma once
// The receiving side of litamin2-map-tiles: a DataReader listener that converts each MapTile
// sample (dds::from_map_tile: invalid ones rejected and counted by reason, never repaired) and
// keeps each tile's newest revision. The samples arrive on Fast DDS's thread; wait() and the
// accessors are for the main thread.

#include "litamin2/dds/map_tile_conversion.hpp"

#include <fastdds/dds/subscriber/DataReaderListener.hpp>

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <utility>

namespace litamin2::map_tiles {

struct CollectorCounts {
  /// Samples with data, accepted, and rejected by TileError name.
  std::uint64_t received = 0;
  std::uint64_t accepted = 0;
  std::map<std::string, std::uint64_t> rejected;
  /// Accepted samples older than (or as old as) the revision already held, ignored.
  std::uint64_t stale = 0;
  /// Samples that could not be taken (deserialisation failed inside Fast DDS).
  std::uint64_t take_failures = 0;
};

class TileCollector : public eprosima::fastdds::dds::DataReaderListener {
 public:
  using Key = std::pair<std::int32_t, std::int32_t>;

  explicit TileCollector(dds::TileConversionOptions options) : options_(options) {}

  void on_data_available(eprosima::fastdds::dds::DataReader* reader) override;

  /// Waits until `count` distinct tiles arrived (0: never) or `deadline`; true if they did.
  bool wait(std::size_t count, std::chrono::steady_clock::time_point deadline);

  std::map<Key, dds::MapTileData> tiles() const;
  CollectorCounts counts() const;

 private:
  dds::TileConversionOptions options_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::map<Key, dds::MapTileData> tiles_;
  CollectorCounts counts_;
  static constexpr std::uint64_t kLoggedRejections = 10;
  std::uint64_t logged_rejections_ = 0;
};

}  // namespace litamin2::map_tiles

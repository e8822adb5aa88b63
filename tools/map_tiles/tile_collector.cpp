#include "map_tiles/tile_collector.hpp"

#include "litamin2/msg/MapTile.h"

#include <spdlog/spdlog.h>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>

namespace litamin2::map_tiles {

namespace fdds = eprosima::fastdds::dds;

void TileCollector::on_data_available(fdds::DataReader* reader) {
  for (;;) {
    litamin2::msg::MapTile msg;
    fdds::SampleInfo info;
    const ReturnCode_t rc = reader->take_next_sample(&msg, &info);
    if (rc == ReturnCode_t::RETCODE_NO_DATA) break;
    std::lock_guard lock(mutex_);
    if (rc != ReturnCode_t::RETCODE_OK) {
      ++counts_.take_failures;
      break;
    }
    if (!info.valid_data) continue;
    ++counts_.received;
    dds::TileConversion c = dds::from_map_tile(msg, options_);
    if (!c.ok()) {
      ++counts_.rejected[dds::to_string(c.error)];
      // The first few in full; the rest are counted (a flood of bad samples floods no log).
      if (++logged_rejections_ <= kLoggedRejections) spdlog::warn("rejected: {}", c.message);
      continue;
    }
    ++counts_.accepted;
    const Key key{c.tile.ix, c.tile.iy};
    const auto it = tiles_.find(key);
    if (it != tiles_.end() && it->second.revision >= c.tile.revision) {
      ++counts_.stale;
      continue;
    }
    spdlog::debug("tile ({}, {}) revision {}: {} distributions", key.first, key.second,
                  c.tile.revision, c.tile.distributions.size());
    tiles_[key] = std::move(c.tile);
    changed_.notify_all();
  }
}

bool TileCollector::wait(std::size_t count, std::chrono::steady_clock::time_point deadline) {
  std::unique_lock lock(mutex_);
  if (count == 0) {
    changed_.wait_until(lock, deadline, [] { return false; });
    return false;
  }
  return changed_.wait_until(lock, deadline, [&] { return tiles_.size() >= count; });
}

std::map<TileCollector::Key, dds::MapTileData> TileCollector::tiles() const {
  std::lock_guard lock(mutex_);
  return tiles_;
}

CollectorCounts TileCollector::counts() const {
  std::lock_guard lock(mutex_);
  return counts_;
}

}  // namespace litamin2::map_tiles

#include "litamin2/aggregator/dds/map_tile_publisher.hpp"

#include "litamin2/aggregator/dds/aggregator_messages.hpp"
#include "litamin2/dds/map_tile_conversion.hpp"
#include "litamin2/dds/time_conversion.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>

namespace litamin2::aggregator {

MapTilePublisher::MapTilePublisher(Write write, double period_s, RevisionClock revision_clock)
    : write_(std::move(write)),
      limiter_(
          std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(period_s))),
      revision_clock_(std::move(revision_clock)) {}

void MapTilePublisher::offer(const TileOutput& tile, Clock::time_point now) {
  litamin2::msg::MapTile msg = to_map_tile_msg(tile, 0, dds::wall_clock_now());
  std::lock_guard lock(mutex_);
  last_revision_ = std::max(last_revision_ + 1, revision_clock_());
  msg.revision(last_revision_);
  if (limiter_.offer(tile.key, now)) {
    write(msg);
    return;
  }
  held_[tile.key] = std::move(msg);
}

void MapTilePublisher::flush_due(Clock::time_point now) {
  std::lock_guard lock(mutex_);
  for (const mapping::TileKey& key : limiter_.take_due(now)) {
    const auto it = held_.find(key);
    if (it == held_.end()) continue;
    write(it->second);
    held_.erase(it);
  }
}

void MapTilePublisher::flush_all() {
  std::lock_guard lock(mutex_);
  limiter_.take_all(Clock::now());
  for (auto& [key, msg] : held_) write(msg);
  held_.clear();
}

MapTileCounters MapTilePublisher::counters() const {
  std::lock_guard lock(mutex_);
  MapTileCounters c;
  c.published = published_;
  c.write_failures = write_failures_;
  c.deferred = limiter_.deferred();
  c.folded = limiter_.folded();
  c.held = held_.size();
  return c;
}

void MapTilePublisher::write(litamin2::msg::MapTile& msg) {
  if (write_(msg)) {
    ++published_;
    return;
  }
  ++write_failures_;
  spdlog::warn("cannot publish map tile ({}, {}) revision {}", msg.ix(), msg.iy(), msg.revision());
}

}  // namespace litamin2::aggregator

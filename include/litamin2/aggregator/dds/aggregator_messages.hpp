#pragma once
/// The aggregator's outputs as DDS messages: KeyframePoses per stream, MapSummary, MapTile, and the
/// status DiagnosticArray (one entry for the aggregator, named "litamin2-aggregator", and one
/// per stream, named "litamin2-aggregator: <stream>").

#include "diagnostic_msgs/msg/DiagnosticArray.h"
#include "litamin2/aggregator/aggregator_outputs.hpp"
#include "litamin2/aggregator/dds/map_odometry_relay.hpp"
#include "litamin2/aggregator/mapping_worker.hpp"
#include "litamin2/msg/KeyframePoses.h"
#include "litamin2/msg/MapSummary.h"
#include "litamin2/msg/MapTile.h"

#include <cstdint>
#include <map>
#include <string>

namespace litamin2::aggregator {

/// frame_id of poses in the shared map frame.
inline constexpr const char* kMapFrame = "map";

litamin2::msg::KeyframePoses to_keyframe_poses_msg(const StreamPoses& poses);
litamin2::msg::MapSummary to_map_summary_msg(const MapSummary& summary, Stamp stamp);
/// A tile in frame "map" (dds::to_map_tile); a gone tile has no distributions and 0 keyframes.
litamin2::msg::MapTile to_map_tile_msg(const TileOutput& tile, std::uint64_t revision, Stamp stamp);

/// What the status reports besides the mapping thread's counters.
struct IngestCounters {
  std::uint64_t received = 0;
  std::uint64_t rejected = 0;
  /// `rejected` by reason ("bad_covariance", "malformed_cdr", ...).
  std::map<std::string, std::uint64_t> rejected_by_reason;
  /// Samples (patches and odometry) that could not be deserialised at all, wherever Fast DDS
  /// deserialised them.
  std::uint64_t malformed_samples = 0;
  std::uint64_t samples_lost = 0;
  int writers = 0;
  std::size_t queued = 0;
  std::size_t queue_capacity = 0;
  std::size_t queue_high_water = 0;
  std::string store_path;
  /// rt/litamin2/map_tiles: tile samples written, and changes held back by
  /// map_tiles.publish_period_s (MapTilePublisher).
  std::uint64_t map_tiles_published = 0;
  std::uint64_t map_tiles_deferred = 0;
};

/// level: 0 OK, 1 WARN (patches rejected or lost since the last status), 2 ERROR (store failed
/// or mapping stalled), with `message`. Each stream's entry also reports its odometry
/// (`odometry`: received, rate, seconds since the last message, map-frame poses published).
diagnostic_msgs::msg::DiagnosticArray make_aggregator_status(
    const WorkerStatus& worker, const IngestCounters& ingest,
    const std::map<std::string, OdometryStreamStatus>& odometry, std::uint8_t level,
    const std::string& message, Stamp stamp);

}  // namespace litamin2::aggregator

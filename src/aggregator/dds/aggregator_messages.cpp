#include "litamin2/aggregator/dds/aggregator_messages.hpp"

#include "litamin2/dds/diagnostics.hpp"
#include "litamin2/dds/map_patch_conversion.hpp"
#include "litamin2/dds/map_tile_conversion.hpp"
#include "litamin2/dds/pose_conversion.hpp"
#include "litamin2/dds/time_conversion.hpp"

#include <algorithm>

namespace litamin2::aggregator {

using dds::fixed_number;
using dds::key_value;

litamin2::msg::KeyframePoses to_keyframe_poses_msg(const StreamPoses& poses) {
  litamin2::msg::KeyframePoses msg;
  msg.stream_id(poses.stream);
  msg.chunk(poses.chunk);
  msg.chunk_keyframes(poses.chunk_keyframes);
  msg.frame_id(poses.in_map_frame ? std::string(kMapFrame) : poses.anchor + "/odom");
  msg.anchor_stream(poses.anchor);
  msg.in_map_frame(poses.in_map_frame);
  msg.correction(dds::to_pose_msg(poses.correction));
  auto& out = msg.keyframes();
  out.reserve(poses.keyframes.size());
  for (const StreamPoses::Entry& e : poses.keyframes) {
    litamin2::msg::KeyframePose p;
    p.keyframe_id(e.id);
    p.stamp(dds::to_time(e.stamp));
    p.pose(dds::to_pose_msg(e.pose));
    out.push_back(std::move(p));
  }
  return msg;
}

litamin2::msg::MapTile to_map_tile_msg(const TileOutput& tile, std::uint64_t revision,
                                       Stamp stamp) {
  dds::MapTileData data;
  data.ix = tile.key.ix;
  data.iy = tile.key.iy;
  data.tile_size = tile.tile_size;
  data.voxel_size = tile.voxel_size;
  data.revision = revision;
  data.stamp = stamp;
  data.frame_id = kMapFrame;
  data.anchor_stream = tile.anchor;
  data.keyframes = static_cast<std::uint64_t>(std::max<std::int64_t>(tile.keyframes, 0));
  data.distributions = tile.distributions;
  return dds::to_map_tile(data);
}

litamin2::msg::MapSummary to_map_summary_msg(const MapSummary& s, Stamp stamp) {
  litamin2::msg::MapSummary msg;
  msg.stamp(dds::to_time(stamp));
  msg.frame_id(kMapFrame);
  msg.anchor_stream(s.anchor);
  msg.voxel_size(static_cast<float>(s.voxel_size));
  msg.voxels(s.voxels);
  msg.keyframes(s.keyframes);
  msg.streams(static_cast<std::uint32_t>(s.streams));
  msg.loops(static_cast<std::uint32_t>(s.loops));
  msg.optimizations(static_cast<std::uint32_t>(s.optimizations));
  msg.min_bound({static_cast<float>(s.min_bound.x()), static_cast<float>(s.min_bound.y()),
                 static_cast<float>(s.min_bound.z())});
  msg.max_bound({static_cast<float>(s.max_bound.x()), static_cast<float>(s.max_bound.y()),
                 static_cast<float>(s.max_bound.z())});
  auto& means = msg.means();
  means.reserve(3 * s.means.size());
  for (const Eigen::Vector3f& m : s.means) means.insert(means.end(), {m.x(), m.y(), m.z()});
  return msg;
}

diagnostic_msgs::msg::DiagnosticArray make_aggregator_status(
    const WorkerStatus& w, const IngestCounters& in,
    const std::map<std::string, OdometryStreamStatus>& odometry, std::uint8_t level,
    const std::string& message, Stamp stamp) {
  diagnostic_msgs::msg::DiagnosticArray array;
  array.header().stamp(dds::to_time(stamp));
  array.header().frame_id("");
  diagnostic_msgs::msg::DiagnosticStatus status;
  status.level(level);
  status.name("litamin2-aggregator");
  status.message(message);
  status.hardware_id("litamin2-aggregator");
  auto& v = status.values();
  v.push_back(key_value("store", in.store_path));
  v.push_back(key_value("writers", std::to_string(in.writers)));
  v.push_back(key_value("patches_received", std::to_string(in.received)));
  v.push_back(key_value("patches_rejected", std::to_string(in.rejected)));
  for (const auto& [reason, count] : in.rejected_by_reason)
    v.push_back(key_value("patches_rejected." + reason, std::to_string(count)));
  v.push_back(key_value("malformed_samples", std::to_string(in.malformed_samples)));
  v.push_back(key_value("samples_lost", std::to_string(in.samples_lost)));
  v.push_back(key_value("queued", std::to_string(in.queued)));
  v.push_back(key_value("queue_capacity", std::to_string(in.queue_capacity)));
  v.push_back(key_value("queue_high_water", std::to_string(in.queue_high_water)));
  v.push_back(key_value("keyframes", std::to_string(w.keyframes)));
  v.push_back(key_value("keyframes_recovered", std::to_string(w.recovered)));
  v.push_back(key_value("duplicates", std::to_string(w.duplicates)));
  v.push_back(key_value("streams", std::to_string(w.streams.size())));
  v.push_back(key_value("loops", std::to_string(w.loops)));
  v.push_back(key_value("optimizations", std::to_string(w.optimizations)));
  v.push_back(key_value("batches", std::to_string(w.batches)));
  v.push_back(key_value("last_store_ms", fixed_number(w.last_store_ms, 3)));
  v.push_back(key_value("last_mapper_ms", fixed_number(w.last_mapper_ms, 3)));
  v.push_back(key_value("last_optimize_ms", fixed_number(w.last_optimize_ms, 3)));
  if (!w.error.empty()) v.push_back(key_value("error", w.error));
  array.status().push_back(std::move(status));
  for (const auto& [stream, counts] : w.streams) {
    diagnostic_msgs::msg::DiagnosticStatus s;
    const std::uint64_t missing = counts.max_id + 1 - counts.keyframes;
    s.level(missing > 0 ? 1 : 0);
    s.name("litamin2-aggregator: " + stream);
    s.message(missing > 0 ? "keyframes missing (late or lost patches)" : "ok");
    s.hardware_id(stream);
    s.values().push_back(key_value("keyframes", std::to_string(counts.keyframes)));
    s.values().push_back(key_value("max_keyframe_id", std::to_string(counts.max_id)));
    s.values().push_back(key_value("missing", std::to_string(missing)));
    const auto o = odometry.find(stream);
    if (o != odometry.end()) {
      const OdometryStreamStatus& c = o->second;
      s.values().push_back(key_value("odometry_received", std::to_string(c.received)));
      s.values().push_back(key_value("odometry_rate_hz", fixed_number(c.rate_hz, 2)));
      s.values().push_back(key_value(
          "odometry_last_seen_s", c.last_seen_s < 0.0 ? "never" : fixed_number(c.last_seen_s, 3)));
      s.values().push_back(key_value("odometry_rejected", std::to_string(c.rejected)));
      s.values().push_back(
          key_value("odometry_before_keyframe", std::to_string(c.before_keyframe)));
      s.values().push_back(key_value("map_odometry_published", std::to_string(c.published)));
      s.values().push_back(key_value("map_odometry_frame", c.frame_id));
    }
    array.status().push_back(std::move(s));
  }
  return array;
}

}  // namespace litamin2::aggregator

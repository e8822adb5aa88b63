#pragma once
/// The TF frame names of one stream (docs/ros2.md, "Frames"): REP-105's odom and base_link,
/// plus the sensor, each "<stream>/<name>" when outputs.frame_prefix is set (the default: every
/// stream is its own tree, as several vehicles on one domain need) and the name as given
/// otherwise. A stream's own sensor_frame is used verbatim.

#include "litamin2/daemon/daemon_config.hpp"

#include <optional>
#include <string>

namespace litamin2::daemon {

struct StreamFrames {
  /// frame_id of the stream's odometry and map patches; parent of base on rt/tf.
  std::string odom;
  /// child_frame_id of the odometry; the published pose is this frame's.
  std::string base;
  /// Child of base on rt/tf_static (the extrinsic).
  std::string sensor;
};

StreamFrames stream_frames(const OutputsConfig& outputs, const StreamConfig& stream);

/// Why `name` cannot be a tf2 frame id (std::nullopt when it can): empty, a leading '/' (tf2
/// rejects it), or whitespace or control characters.
std::optional<std::string> frame_name_error(const std::string& name);

}  // namespace litamin2::daemon

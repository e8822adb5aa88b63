#include "litamin2/daemon/stream_frames.hpp"

namespace litamin2::daemon {

StreamFrames stream_frames(const OutputsConfig& outputs, const StreamConfig& stream) {
  const std::string prefix = outputs.frame_prefix ? stream.id + "/" : std::string();
  StreamFrames frames;
  frames.odom = prefix + outputs.odom_frame;
  frames.base = prefix + outputs.base_frame;
  frames.sensor = stream.sensor_frame.empty() ? prefix + outputs.sensor_frame : stream.sensor_frame;
  return frames;
}

std::optional<std::string> frame_name_error(const std::string& name) {
  if (name.empty()) return "must not be empty";
  if (name.front() == '/') return "must not start with '/' (tf2 refuses such frame ids)";
  for (const char c : name) {
    const auto u = static_cast<unsigned char>(c);
    if (u <= 0x20 || u == 0x7f) return "must not hold whitespace or control characters";
  }
  return std::nullopt;
}

}  // namespace litamin2::daemon

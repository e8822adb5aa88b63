#include "litamin2/daemon/daemon_config.hpp"

#include "litamin2/core/config_error.hpp"
#include "litamin2/daemon/membership.hpp"
#include "litamin2/daemon/stream_frames.hpp"
#include "litamin2/service/logging.hpp"
#include "litamin2/service/topic_names.hpp"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <set>
#include <string_view>

namespace litamin2::daemon {
namespace {

void check_topic(const std::string& topic, const std::string& path) {
  if (const auto why = service::topic_name_error(topic)) throw ConfigError(path + ": " + *why);
}

void check_frame(const std::string& name, const std::string& path) {
  if (const auto why = frame_name_error(name))
    throw ConfigError(path + ": '" + name + "' is not a frame name: " + *why);
}

}  // namespace

int prefault_auto_mb(const DaemonConfig& config) {
  constexpr std::size_t kBaseMiB = 64;
  constexpr std::size_t kPerStreamMiB = 32;
  constexpr std::size_t kAutoMaxMiB = 1024;
  const std::size_t streams = std::max<std::size_t>(1, config.streams.size());
  return static_cast<int>(std::min(kBaseMiB + kPerStreamMiB * streams, kAutoMaxMiB));
}

std::size_t prefault_bytes(const DaemonConfig& config) {
  const int mib = config.memory.prefault_mb ? *config.memory.prefault_mb : prefault_auto_mb(config);
  return static_cast<std::size_t>(std::max(mib, 0)) << 20;
}

void validate(const DaemonConfig& config) {
  std::set<std::string> ids, topics;
  for (std::size_t i = 0; i < config.streams.size(); ++i) {
    const StreamConfig& stream = config.streams[i];
    const std::string path = "streams[" + std::to_string(i) + "]";
    if (const auto why = service::stream_id_error(stream.id))
      throw ConfigError(path + ".id: '" + stream.id + "' is not a valid stream id: " + *why);
    if (!ids.insert(stream.id).second)
      throw ConfigError(path + ".id: duplicate stream id '" + stream.id + "'");
    if (stream.inputs.empty()) {
      check_topic(stream.topic, path + ".topic");
      if (!topics.insert(stream.topic).second)
        throw ConfigError(path + ".topic: '" + stream.topic + "' is used by another stream");
    } else {
      if (!stream.topic.empty())
        throw ConfigError(path + ".topics: give topic or topics, not both");
      if (!stream.extrinsic.matrix().isIdentity(0.0))
        throw ConfigError(path +
                          ".extrinsic: a stream with topics gives each topic's extrinsic instead");
      for (std::size_t j = 0; j < stream.inputs.size(); ++j) {
        const SensorInput& input = stream.inputs[j];
        const std::string input_path = path + ".topics[" + std::to_string(j) + "]";
        check_topic(input.topic, input_path + ".topic");
        if (!topics.insert(input.topic).second)
          throw ConfigError(input_path + ".topic: '" + input.topic +
                            "' is used by another stream or input");
        if (const auto why = extrinsic_error(input.extrinsic))
          throw ConfigError(input_path + ".extrinsic: " + *why);
      }
      if (const auto why = scan_merger_config_error(stream.merge))
        throw ConfigError(path + "." + *why);
    }
    if (!stream.zero_copy_topic.empty()) {
      if (!stream.inputs.empty())
        throw ConfigError(path + ".zero_copy_topic: only for a stream of one topic");
      check_topic(stream.zero_copy_topic, path + ".zero_copy_topic");
      if (!topics.insert(stream.zero_copy_topic).second)
        throw ConfigError(path + ".zero_copy_topic: '" + stream.zero_copy_topic +
                          "' is used by another stream or input");
    }
    if (!stream.sensor_frame.empty()) check_frame(stream.sensor_frame, path + ".sensor_frame");
    try {
      validate(stream.tracker);
    } catch (const ConfigError& e) {
      throw ConfigError(path + ".tracker." + e.what());
    }
  }
  std::string why;
  if (!service::TopicPattern::parse(config.discovery.pattern, &why))
    throw ConfigError("discovery.pattern: " + why);
  check_topic(config.outputs.odom_suffix, "outputs.odom_suffix");
  check_topic(config.outputs.map_patches_topic, "outputs.map_patches_topic");
  check_topic(config.outputs.status_topic, "outputs.status_topic");
  if (!config.outputs.diagnostics_topic.empty()) {
    check_topic(config.outputs.diagnostics_topic, "outputs.diagnostics_topic");
    if (config.outputs.diagnostics_topic == config.outputs.status_topic)
      throw ConfigError("outputs.diagnostics_topic: equals outputs.status_topic");
  }
  if (const auto why = service::metrics_config_error(config.metrics)) throw ConfigError(*why);
  const OutputsConfig& out = config.outputs;
  check_frame(out.odom_frame, "outputs.odom_frame");
  check_frame(out.base_frame, "outputs.base_frame");
  check_frame(out.sensor_frame, "outputs.sensor_frame");
  if (out.odom_frame == out.base_frame)
    throw ConfigError("outputs.base_frame: equals outputs.odom_frame ('" + out.odom_frame + "')");
  if (!out.frame_prefix && (config.streams.size() > 1 || config.discovery.enabled))
    throw ConfigError(
        "outputs.frame_prefix: false needs exactly one configured stream and no discovery "
        "(the streams' frames would have the same names)");
  check_topic(out.tf_topic, "outputs.tf_topic");
  check_topic(out.tf_static_topic, "outputs.tf_static_topic");
  if (out.tf_topic == out.tf_static_topic)
    throw ConfigError("outputs.tf_static_topic: equals outputs.tf_topic");
  const auto& levels = service::kLogLevels;
  if (const auto why = worker_scheduling_error(config.scheduling))
    throw ConfigError("scheduling." + *why);
  if (std::find(levels.begin(), levels.end(), std::string_view(config.log_level)) == levels.end())
    throw ConfigError("log_level: '" + config.log_level + "' is not a log level");
  if (config.streams.empty() && !config.discovery.enabled)
    throw ConfigError("streams: no streams configured and discovery.enabled is false");
  if (config.memory.prefault_mb &&
      (*config.memory.prefault_mb < 0 || *config.memory.prefault_mb > kMaxPrefaultMiB))
    throw ConfigError("memory.prefault_mb: " + std::to_string(*config.memory.prefault_mb) +
                      " is out of range [0, " + std::to_string(kMaxPrefaultMiB) + "]");
  if (!config.member_id.empty())
    if (const auto why = member_id_error(config.member_id))
      throw ConfigError("member_id: '" + config.member_id + "' is not a member id: " + *why);
  const ShardingConfig& sharding = config.sharding;
  if (sharding.enabled && !config.discovery.enabled)
    throw ConfigError("sharding.enabled: needs discovery.enabled (only discovered streams move)");
  if (sharding.enabled && !config.streams.empty())
    throw ConfigError(
        "sharding.enabled: configured streams would be tracked by every daemon; use discovery");
  if (!(sharding.startup_wait_s >= 0.0)) throw ConfigError("sharding.startup_wait_s: must be >= 0");
  if (!(sharding.max_extrapolation_s >= 0.0))
    throw ConfigError("sharding.max_extrapolation_s: must be >= 0");
  if (sharding.seed_keyframes < 0 || sharding.seed_keyframes > 1000)
    throw ConfigError("sharding.seed_keyframes: must be in [0, 1000]");
  if (!(sharding.seed_max_age_s > 0.0)) throw ConfigError("sharding.seed_max_age_s: must be > 0");
  if (sharding.replicas < 1 || sharding.replicas > 8)
    throw ConfigError("sharding.replicas: must be in [1, 8]");
  if (sharding.replicas > 1 && !sharding.enabled)
    throw ConfigError("sharding.replicas: needs sharding.enabled (standbys follow the members)");
}

std::string resolved_member_id(const DaemonConfig& config) {
  if (!config.member_id.empty()) return config.member_id;
  std::array<char, 256> name{};
  if (gethostname(name.data(), name.size() - 1) != 0)
    throw ConfigError("member_id: not set and the host name is unknown");
  const std::string host(name.data());
  if (const auto why = member_id_error(host))
    throw ConfigError("member_id: not set and the host name '" + host + "' is not a member id (" +
                      *why + "); set member_id");
  return host;
}

TrackerConfig daemon_tracker_defaults() {
  TrackerConfig config;
  config.deskew.enabled = true;
  return config;
}

StreamConfig discovered_stream(const DaemonConfig& config, const std::string& id,
                               const std::string& topic) {
  StreamConfig stream;
  stream.id = id;
  stream.topic = topic;
  stream.tracker = config.tracker;
  return stream;
}

}  // namespace litamin2::daemon

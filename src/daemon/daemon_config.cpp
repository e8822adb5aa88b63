#include "litamin2/daemon/daemon_config.hpp"

#include "litamin2/core/config_error.hpp"
#include "litamin2/service/logging.hpp"
#include "litamin2/service/topic_names.hpp"

#include <algorithm>
#include <set>
#include <string_view>

namespace litamin2::daemon {
namespace {

void check_topic(const std::string& topic, const std::string& path) {
  if (const auto why = service::topic_name_error(topic)) throw ConfigError(path + ": " + *why);
}

}  // namespace

void validate(const DaemonConfig& config) {
  std::set<std::string> ids, topics;
  for (std::size_t i = 0; i < config.streams.size(); ++i) {
    const StreamConfig& stream = config.streams[i];
    const std::string path = "streams[" + std::to_string(i) + "]";
    if (const auto why = service::stream_id_error(stream.id))
      throw ConfigError(path + ".id: '" + stream.id + "' is not a valid stream id: " + *why);
    if (!ids.insert(stream.id).second)
      throw ConfigError(path + ".id: duplicate stream id '" + stream.id + "'");
    check_topic(stream.topic, path + ".topic");
    if (!topics.insert(stream.topic).second)
      throw ConfigError(path + ".topic: '" + stream.topic + "' is used by another stream");
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
  if (config.outputs.odom_frame.empty()) throw ConfigError("outputs.odom_frame: must not be empty");
  const auto& levels = service::kLogLevels;
  if (std::find(levels.begin(), levels.end(), std::string_view(config.log_level)) == levels.end())
    throw ConfigError("log_level: '" + config.log_level + "' is not a log level");
  if (config.streams.empty() && !config.discovery.enabled)
    throw ConfigError("streams: no streams configured and discovery.enabled is false");
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

#include "litamin2/aggregator/aggregator_config.hpp"

#include "litamin2/core/config_error.hpp"
#include "litamin2/service/logging.hpp"
#include "litamin2/service/topic_names.hpp"

#include <algorithm>
#include <set>
#include <string_view>

namespace litamin2::aggregator {
namespace {

void check_topic(const std::string& topic, const std::string& path) {
  if (const auto why = service::topic_name_error(topic)) throw ConfigError(path + ": " + *why);
}

void check_pattern(const std::string& pattern, const std::string& path) {
  std::string why;
  if (!service::TopicPattern::parse(pattern, &why)) throw ConfigError(path + ": " + why);
}

}  // namespace

void validate(const AggregatorConfig& config) {
  const TopicsConfig& t = config.topics;
  check_topic(t.map_patches, "topics.map_patches");
  check_topic(t.keyframe_poses, "topics.keyframe_poses");
  check_topic(t.map_summary, "topics.map_summary");
  check_topic(t.status, "topics.status");
  check_topic(t.map_tiles, "topics.map_tiles");
  const std::set<std::string> distinct = {t.map_patches, t.keyframe_poses, t.map_summary, t.status,
                                          t.map_tiles};
  if (distinct.size() != 5) throw ConfigError("topics: the five topics must be different");
  if (!t.odometry.empty()) {
    check_pattern(t.odometry, "topics.odometry");
    check_pattern(t.map_odometry, "topics.map_odometry");
    if (t.odometry == t.map_odometry)
      throw ConfigError("topics: odometry and map_odometry must be different");
  }
  if (!t.tf.empty()) {
    check_topic(t.tf, "topics.tf");
    if (distinct.count(t.tf)) throw ConfigError("topics.tf: '" + t.tf + "' is another topic's");
  }
  if (!t.diagnostics.empty()) {
    check_topic(t.diagnostics, "topics.diagnostics");
    if (distinct.count(t.diagnostics) || t.diagnostics == t.tf)
      throw ConfigError("topics.diagnostics: '" + t.diagnostics + "' is another topic's");
  }
  if (!t.map_cloud.empty()) {
    check_topic(t.map_cloud, "topics.map_cloud");
    if (distinct.count(t.map_cloud) || t.map_cloud == t.tf || t.map_cloud == t.diagnostics)
      throw ConfigError("topics.map_cloud: '" + t.map_cloud + "' is another topic's");
  }
  if (const auto why = service::metrics_config_error(config.metrics)) throw ConfigError(*why);
  if (config.store.path.empty()) throw ConfigError("store.path: must not be empty");
  try {
    mapping::validate(config.mapper);
  } catch (const ConfigError& e) {
    throw ConfigError(std::string("mapper: ") + e.what());
  }
  try {
    mapping::validate(config.map_tiles.tiles);
  } catch (const ConfigError& e) {
    throw ConfigError(std::string("map_tiles.") + e.what());
  }
  if (config.map_tiles.max_keyframes_per_turn < 1)
    throw ConfigError("map_tiles.max_keyframes_per_turn: must be >= 1");
  if (!(config.map_tiles.publish_period_s >= 0.0 && config.map_tiles.publish_period_s <= 3600.0))
    throw ConfigError("map_tiles.publish_period_s: must be in [0, 3600] s");
  if (!(config.map_tiles.persist_period_s >= 0.0 && config.map_tiles.persist_period_s <= 3600.0))
    throw ConfigError("map_tiles.persist_period_s: must be in [0, 3600] s");
  if (config.publish.poses_chunk_keyframes < 0)
    throw ConfigError("publish.poses_chunk_keyframes: must be >= 0");
  const auto& levels = service::kLogLevels;
  if (std::find(levels.begin(), levels.end(), std::string_view(config.log_level)) == levels.end())
    throw ConfigError("log_level: '" + config.log_level + "' is not a log level");
}

}  // namespace litamin2::aggregator

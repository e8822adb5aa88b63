#include "litamin2/aggregator/aggregator_config.hpp"

#include "litamin2/core/yaml_section.hpp"

#include <yaml-cpp/yaml.h>

#include <fstream>
#include <set>

namespace litamin2::aggregator {
namespace {

void check_topic(const std::string& topic, const std::string& path) {
  if (topic.empty()) throw ConfigError(path + ": empty topic name");
  for (char c : topic)
    if (static_cast<unsigned char>(c) <= ' ' || c == '*' || c == '?')
      throw ConfigError(path + ": '" + topic + "' is not a valid topic name");
}

/// A topic pattern with exactly one '*' standing for the stream id (dds::TopicPattern).
void check_pattern(const std::string& pattern, const std::string& path) {
  int stars = 0;
  for (char c : pattern) {
    if (static_cast<unsigned char>(c) <= ' ' || c == '?')
      throw ConfigError(path + ": '" + pattern + "' is not a valid topic pattern");
    stars += c == '*';
  }
  if (stars != 1)
    throw ConfigError(path + ": '" + pattern + "' must contain exactly one '*' (the stream id)");
}

mapping::MapperConfig read_mapper(const YAML::Node& node) {
  try {
    return mapping::mapper_config_from_yaml(node ? node : YAML::Node(YAML::NodeType::Map));
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    if (what.rfind("config:", 0) == 0) throw ConfigError("mapper" + what.substr(6));
    throw ConfigError("mapper." + what);
  }
}

}  // namespace

AggregatorConfig aggregator_config_from_yaml(const YAML::Node& node) {
  AggregatorConfig config;
  YamlSection root(node, "");

  config.dds = daemon::dds_config_from_yaml(root.child("dds"));

  {
    YamlSection topics(root.child("topics"), "topics");
    topics.read("map_patches", config.topics.map_patches);
    topics.read("keyframe_poses", config.topics.keyframe_poses);
    topics.read("map_summary", config.topics.map_summary);
    topics.read("status", config.topics.status);
    topics.read("odometry", config.topics.odometry);
    topics.read("map_odometry", config.topics.map_odometry);
    topics.reject_unknown();
    check_topic(config.topics.map_patches, "topics.map_patches");
    check_topic(config.topics.keyframe_poses, "topics.keyframe_poses");
    check_topic(config.topics.map_summary, "topics.map_summary");
    check_topic(config.topics.status, "topics.status");
    const std::set<std::string> distinct = {config.topics.map_patches, config.topics.keyframe_poses,
                                            config.topics.map_summary, config.topics.status};
    if (distinct.size() != 4) throw ConfigError("topics: the four topics must be different");
    if (!config.topics.odometry.empty()) {
      check_pattern(config.topics.odometry, "topics.odometry");
      check_pattern(config.topics.map_odometry, "topics.map_odometry");
      if (config.topics.odometry == config.topics.map_odometry)
        throw ConfigError("topics: odometry and map_odometry must be different");
    }
  }

  {
    YamlSection store(root.child("store"), "store");
    store.read("path", config.store.path);
    store.read("synchronous_full", config.store.synchronous_full);
    store.reject_unknown();
    if (config.store.path.empty()) throw ConfigError("store.path: must not be empty");
  }

  {
    YamlSection ingest(root.child("ingest"), "ingest");
    ingest.read_range("queue_capacity", config.ingest.queue_capacity, 1, 1'000'000);
    ingest.read_range("max_batch", config.ingest.max_batch, 1, 100'000);
    ingest.reject_unknown();
  }

  {
    YamlSection publish(root.child("publish"), "publish");
    publish.read_range("poses_period_s", config.publish.poses_period_s, 0.0, 3600.0);
    publish.read_range("summary_period_s", config.publish.summary_period_s, 0.0, 86400.0);
    publish.read_range("summary_max_means", config.publish.summary_max_means, 0, 10'000'000);
    publish.read_range("status_period_s", config.publish.status_period_s, 0.01, 3600.0);
    publish.reject_unknown();
  }

  config.mapper = read_mapper(root.child("mapper"));

  {
    YamlSection watchdog(root.child("watchdog"), "watchdog");
    watchdog.read("enabled", config.watchdog.enabled);
    watchdog.read_range("stall_timeout_s", config.watchdog.stall_timeout_s, 0.1, 86400.0);
    watchdog.reject_unknown();
  }

  root.read_enum<std::string>("log_level", config.log_level,
                              {{"trace", "trace"},
                               {"debug", "debug"},
                               {"info", "info"},
                               {"warn", "warn"},
                               {"error", "error"},
                               {"critical", "critical"},
                               {"off", "off"}});
  root.reject_unknown();
  return config;
}

AggregatorConfig load_aggregator_config(const std::string& path) {
  if (!std::ifstream(path)) throw ConfigError(path + ": cannot open the config file");
  YAML::Node node;
  try {
    node = YAML::LoadFile(path);
  } catch (const YAML::Exception& e) {
    throw ConfigError(path + ": not valid YAML: " + e.what());
  }
  try {
    return aggregator_config_from_yaml(node);
  } catch (const ConfigError& e) {
    throw ConfigError(path + ": " + e.what());
  }
}

}  // namespace litamin2::aggregator

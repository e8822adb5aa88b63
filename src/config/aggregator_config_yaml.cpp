#include "litamin2/config/aggregator_config_yaml.hpp"

#include "litamin2/config/config_file.hpp"
#include "litamin2/config/mapper_config_yaml.hpp"
#include "litamin2/config/service_config_yaml.hpp"
#include "litamin2/config/yaml_section.hpp"

namespace litamin2::aggregator {

using config::load_config_file;
using config::read_section;
using config::YamlSection;

AggregatorConfig aggregator_config_from_yaml(const YAML::Node& node) {
  AggregatorConfig config;
  YamlSection root(node, "");

  config.dds = service::transport_config_from_yaml(root.child("dds"));
  config.security = service::security_config_from_yaml(root.child("security"));
  {
    YamlSection limits(root.child("limits"), "limits");
    limits.read_range("max_distributions_per_patch", config.limits.max_distributions_per_patch, 1,
                      10'000'000);
    limits.reject_unknown();
  }

  {
    YamlSection topics(root.child("topics"), "topics");
    topics.read("map_patches", config.topics.map_patches);
    topics.read("keyframe_poses", config.topics.keyframe_poses);
    topics.read("map_summary", config.topics.map_summary);
    topics.read("status", config.topics.status);
    topics.read("odometry", config.topics.odometry);
    topics.read("map_odometry", config.topics.map_odometry);
    topics.reject_unknown();
  }

  {
    YamlSection store(root.child("store"), "store");
    store.read("path", config.store.path);
    store.read("synchronous_full", config.store.synchronous_full);
    store.reject_unknown();
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

  const YAML::Node mapper = root.child("mapper");
  config.mapper = read_section("mapper", [&] {
    return mapping::mapper_config_from_yaml(mapper ? mapper : YAML::Node(YAML::NodeType::Map));
  });
  config.watchdog = service::watchdog_config_from_yaml(root.child("watchdog"), 86400.0);
  service::read_log_level(root, config.log_level);
  root.reject_unknown();
  validate(config);
  return config;
}

AggregatorConfig load_aggregator_config(const std::string& path) {
  return load_config_file(path, aggregator_config_from_yaml);
}

}  // namespace litamin2::aggregator

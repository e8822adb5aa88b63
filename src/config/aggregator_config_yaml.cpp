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
    limits.read("fixed_patch_payloads", config.limits.fixed_patch_payloads);
    limits.reject_unknown();
  }

  {
    YamlSection topics(root.child("topics"), "topics");
    topics.read("map_patches", config.topics.map_patches);
    topics.read("keyframe_poses", config.topics.keyframe_poses);
    topics.read("map_summary", config.topics.map_summary);
    topics.read("map_tiles", config.topics.map_tiles);
    topics.read("status", config.topics.status);
    topics.read("diagnostics", config.topics.diagnostics);
    topics.read("odometry", config.topics.odometry);
    topics.read("map_odometry", config.topics.map_odometry);
    topics.read("tf", config.topics.tf);
    topics.read("map_cloud", config.topics.map_cloud);
    topics.reject_unknown();
  }

  {
    YamlSection store(root.child("store"), "store");
    store.read("path", config.store.path);
    store.read("synchronous_full", config.store.synchronous_full);
    store.read_range("distribution_cache_mb", config.store.distribution_cache_mb, 1, 1'000'000);
    store.read_range("restart_readers", config.store.restart_readers, 1, 64);
    store.read_range("sqlite_cache_mb", config.store.sqlite_cache_mb, 1, 65536);
    store.read_enum("page_size_kb", config.store.page_size_kb,
                    {{"1", 1}, {"2", 2}, {"4", 4}, {"8", 8}, {"16", 16}, {"32", 32}, {"64", 64}});
    store.reject_unknown();
  }

  {
    YamlSection ingest(root.child("ingest"), "ingest");
    ingest.read_range("queue_capacity", config.ingest.queue_capacity, 1, 1'000'000);
    ingest.read_range("max_batch", config.ingest.max_batch, 1, 100'000);
    ingest.read("exclusive_odometry", config.ingest.exclusive_odometry);
    ingest.reject_unknown();
  }

  {
    YamlSection publish(root.child("publish"), "publish");
    publish.read_range("poses_period_s", config.publish.poses_period_s, 0.0, 3600.0);
    publish.read_range("summary_period_s", config.publish.summary_period_s, 0.0, 86400.0);
    publish.read_range("poses_chunk_keyframes", config.publish.poses_chunk_keyframes, 0,
                       10'000'000);
    publish.read_range("summary_max_means", config.publish.summary_max_means, 0, 10'000'000);
    publish.read_range("tiles_period_s", config.publish.tiles_period_s, 0.0, 86400.0);
    publish.read_range("status_period_s", config.publish.status_period_s, 0.01, 3600.0);
    publish.read_range("map_frame_settle_s", config.publish.map_frame_settle_s, 0.0, 600.0);
    publish.reject_unknown();
  }

  const YAML::Node mapper = root.child("mapper");
  config.mapper = read_section("mapper", [&] {
    return mapping::mapper_config_from_yaml(mapper ? mapper : YAML::Node(YAML::NodeType::Map));
  });
  {
    YamlSection tiles(root.child("map_tiles"), "map_tiles");
    mapping::TileMapConfig& t = config.map_tiles.tiles;
    tiles.read_range("tile_size", t.tile_size, 1.0, 100'000.0);
    tiles.read_range("move_threshold_m", t.move_threshold_m, 0.0, 1000.0);
    tiles.read_range("move_threshold_deg", t.move_threshold_deg, 0.0, 180.0);
    tiles.read_range("segment_keyframes", t.segment_keyframes, 0, 100'000);
    tiles.read_range("segment_cache_mb", t.segment_cache_mb, 0.0, 1'000'000.0);
    tiles.read_range("max_keyframes_per_turn", config.map_tiles.max_keyframes_per_turn, 1,
                     10'000'000);
    tiles.read_range("cache_mb", config.map_tiles.cache_mb, 1, 1'000'000);
    tiles.read_range("publish_period_s", config.map_tiles.publish_period_s, 0.0, 3600.0);
    tiles.read_range("persist_period_s", config.map_tiles.persist_period_s, 0.0, 3600.0);
    tiles.reject_unknown();
  }
  {
    YamlSection full_pass(root.child("full_pass"), "full_pass");
    full_pass.read_range("max_duty", config.full_pass.max_duty, 0.0, 1.0);
    full_pass.read_range("min_interval_s", config.full_pass.min_interval_s, 0.0, 86400.0);
    full_pass.read("on_stop", config.full_pass.on_stop);
    full_pass.reject_unknown();
  }
  {
    YamlSection standby(root.child("standby"), "standby");
    // DDS's strength is unsigned 32 bit; the limit keeps it an int here.
    standby.read_range("strength", config.standby.strength, 0, 1'000'000);
    standby.reject_unknown();
  }
  config.watchdog =
      service::watchdog_config_from_yaml(root.child("watchdog"), 86400.0, config.watchdog);
  config.metrics = service::metrics_config_from_yaml(root.child("metrics"));
  service::read_log_level(root, config.log_level);
  root.reject_unknown();
  validate(config);
  return config;
}

AggregatorConfig load_aggregator_config(const std::string& path) {
  return load_config_file(path, aggregator_config_from_yaml);
}

}  // namespace litamin2::aggregator

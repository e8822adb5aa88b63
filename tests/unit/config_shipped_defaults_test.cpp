// The shipped configuration files (config/*.yaml) hold the code's defaults: a file that gives only
// what it must (the dds section) behaves as the shipped file does. Each file is loaded with its
// own loader and compared, field by field, with the struct loaded from a minimal file.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "litamin2/config/aggregator_config_yaml.hpp"
#include "litamin2/config/daemon_config_yaml.hpp"
#include "litamin2/config/mapper_config_yaml.hpp"
#include "litamin2/config/tracker_config_yaml.hpp"

#include <yaml-cpp/yaml.h>

namespace {

using namespace litamin2;
namespace fs = std::filesystem;

const std::string kConfigDir = std::string(LITAMIN2_SOURCE_DIR) + "/config/";

void expect_same_transport(const service::TransportConfig& a, const service::TransportConfig& b) {
  EXPECT_EQ(a.domain, b.domain);
  EXPECT_EQ(a.profile, b.profile);
  EXPECT_EQ(a.xml_file, b.xml_file);
  EXPECT_EQ(a.xml_profile, b.xml_profile);
}

void expect_same_security(const service::SecurityConfig& a, const service::SecurityConfig& b) {
  EXPECT_EQ(a.enabled, b.enabled);
  for (const auto& [name, field] : service::SecurityConfig::kFiles)
    EXPECT_EQ(a.*field, b.*field) << name;
}

void expect_same_watchdog(const service::WatchdogConfig& a, const service::WatchdogConfig& b) {
  EXPECT_EQ(a.enabled, b.enabled);
  EXPECT_EQ(a.stall_timeout_s, b.stall_timeout_s);
}

TEST(ConfigShippedDefaults, EveryShippedFileIsCompared) {
  // A new config file needs a comparison below.
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(kConfigDir)) {
    if (entry.path().extension() != ".yaml") continue;
    const std::string name = entry.path().filename().string();
    EXPECT_TRUE(name == "tracker.yaml" || name == "mapper.yaml" || name == "litamin2d.yaml" ||
                name == "litamin2-aggregator.yaml")
        << name << " has no defaults test";
    ++files;
  }
  EXPECT_EQ(files, 4u);
}

TEST(ConfigShippedDefaults, TrackerFileHoldsTheCodeDefaults) {
  const TrackerConfig shipped = load_tracker_config(kConfigDir + "tracker.yaml");
  const TrackerConfig defaults;
  EXPECT_EQ(tracker_config_to_yaml(shipped), tracker_config_to_yaml(defaults));
  // The keys a sensor preset sets are commented out in the file, so the preset still applies.
  EXPECT_TRUE(shipped.explicit_keys.empty()) << *shipped.explicit_keys.begin();
}

TEST(ConfigShippedDefaults, MapperFileHoldsTheCodeDefaults) {
  const mapping::MapperConfig shipped = mapping::load_mapper_config(kConfigDir + "mapper.yaml");
  EXPECT_EQ(mapping::mapper_config_to_yaml(shipped),
            mapping::mapper_config_to_yaml(mapping::MapperConfig{}));
}

TEST(ConfigShippedDefaults, DaemonDdsOnlyConfigBehavesAsTheShippedFile) {
  using namespace litamin2::daemon;
  const DaemonConfig shipped = load_daemon_config(kConfigDir + "litamin2d.yaml");
  const DaemonConfig minimal =
      daemon_config_from_yaml(YAML::Load("dds: {domain: 0, profile: loopback}"));
  expect_same_transport(shipped.dds, minimal.dds);
  expect_same_security(shipped.security, minimal.security);
  EXPECT_EQ(shipped.limits.max_points_per_scan, minimal.limits.max_points_per_scan);
  EXPECT_EQ(shipped.streams.size(), minimal.streams.size());
  EXPECT_EQ(shipped.discovery.enabled, minimal.discovery.enabled);
  EXPECT_EQ(shipped.discovery.pattern, minimal.discovery.pattern);
  EXPECT_EQ(shipped.discovery.max_streams, minimal.discovery.max_streams);
  EXPECT_EQ(shipped.member_id, minimal.member_id);
  EXPECT_EQ(shipped.sharding.enabled, minimal.sharding.enabled);
  EXPECT_EQ(shipped.sharding.startup_wait_s, minimal.sharding.startup_wait_s);
  EXPECT_EQ(shipped.sharding.max_extrapolation_s, minimal.sharding.max_extrapolation_s);
  EXPECT_EQ(shipped.sharding.seed_keyframes, minimal.sharding.seed_keyframes);
  EXPECT_EQ(shipped.sharding.seed_max_age_s, minimal.sharding.seed_max_age_s);
  EXPECT_EQ(shipped.sharding.replicas, minimal.sharding.replicas);
  EXPECT_EQ(tracker_config_to_yaml(shipped.tracker), tracker_config_to_yaml(minimal.tracker));
  EXPECT_EQ(shipped.threads, minimal.threads);
  EXPECT_EQ(shipped.queue_depth, minimal.queue_depth);
  EXPECT_EQ(shipped.memory.prefault_mb, minimal.memory.prefault_mb);
  EXPECT_EQ(prefault_bytes(shipped), prefault_bytes(minimal));
  EXPECT_EQ(shipped.outputs.odom_suffix, minimal.outputs.odom_suffix);
  EXPECT_EQ(shipped.outputs.map_patches_topic, minimal.outputs.map_patches_topic);
  EXPECT_EQ(shipped.outputs.status_topic, minimal.outputs.status_topic);
  EXPECT_EQ(shipped.outputs.diagnostics_topic, minimal.outputs.diagnostics_topic);
  EXPECT_EQ(shipped.metrics.listen, minimal.metrics.listen);
  EXPECT_EQ(shipped.outputs.status_period_s, minimal.outputs.status_period_s);
  EXPECT_EQ(shipped.outputs.map_patch_history, minimal.outputs.map_patch_history);
  EXPECT_EQ(shipped.outputs.odom_frame, minimal.outputs.odom_frame);
  expect_same_watchdog(shipped.watchdog, minimal.watchdog);
  EXPECT_EQ(shipped.log_level, minimal.log_level);
  EXPECT_EQ(shipped.shutdown_timeout_s, minimal.shutdown_timeout_s);
}

TEST(ConfigShippedDefaults, AggregatorDdsOnlyConfigBehavesAsTheShippedFile) {
  using namespace litamin2::aggregator;
  const AggregatorConfig shipped = load_aggregator_config(kConfigDir + "litamin2-aggregator.yaml");
  const AggregatorConfig minimal =
      aggregator_config_from_yaml(YAML::Load("dds: {domain: 0, profile: loopback}"));
  expect_same_transport(shipped.dds, minimal.dds);
  expect_same_security(shipped.security, minimal.security);
  EXPECT_EQ(shipped.limits.max_distributions_per_patch, minimal.limits.max_distributions_per_patch);
  const TopicsConfig &st = shipped.topics, &mt = minimal.topics;
  EXPECT_EQ(st.map_patches, mt.map_patches);
  EXPECT_EQ(st.keyframe_poses, mt.keyframe_poses);
  EXPECT_EQ(st.map_summary, mt.map_summary);
  EXPECT_EQ(st.map_tiles, mt.map_tiles);
  EXPECT_EQ(st.status, mt.status);
  EXPECT_EQ(st.diagnostics, mt.diagnostics);
  EXPECT_EQ(shipped.metrics.listen, minimal.metrics.listen);
  EXPECT_EQ(st.odometry, mt.odometry);
  EXPECT_EQ(st.map_odometry, mt.map_odometry);
  EXPECT_EQ(shipped.store.path, minimal.store.path);
  EXPECT_EQ(shipped.store.synchronous_full, minimal.store.synchronous_full);
  EXPECT_EQ(shipped.store.distribution_cache_mb, minimal.store.distribution_cache_mb);
  EXPECT_EQ(shipped.store.restart_readers, minimal.store.restart_readers);
  EXPECT_EQ(shipped.store.page_size_kb, minimal.store.page_size_kb);
  EXPECT_EQ(shipped.store.sqlite_cache_mb, minimal.store.sqlite_cache_mb);
  EXPECT_EQ(shipped.ingest.queue_capacity, minimal.ingest.queue_capacity);
  EXPECT_EQ(shipped.ingest.max_batch, minimal.ingest.max_batch);
  EXPECT_EQ(shipped.ingest.exclusive_odometry, minimal.ingest.exclusive_odometry);
  const PublishConfig &sp = shipped.publish, &mp = minimal.publish;
  EXPECT_EQ(sp.poses_period_s, mp.poses_period_s);
  EXPECT_EQ(sp.poses_chunk_keyframes, mp.poses_chunk_keyframes);
  EXPECT_EQ(sp.summary_period_s, mp.summary_period_s);
  EXPECT_EQ(sp.summary_max_means, mp.summary_max_means);
  EXPECT_EQ(sp.tiles_period_s, mp.tiles_period_s);
  EXPECT_EQ(sp.map_frame_settle_s, mp.map_frame_settle_s);
  EXPECT_EQ(sp.status_period_s, mp.status_period_s);
  EXPECT_EQ(mapping::mapper_config_to_yaml(shipped.mapper),
            mapping::mapper_config_to_yaml(minimal.mapper));
  EXPECT_EQ(shipped.map_tiles.tiles.tile_size, minimal.map_tiles.tiles.tile_size);
  EXPECT_EQ(shipped.map_tiles.tiles.move_threshold_m, minimal.map_tiles.tiles.move_threshold_m);
  EXPECT_EQ(shipped.map_tiles.tiles.move_threshold_deg, minimal.map_tiles.tiles.move_threshold_deg);
  EXPECT_EQ(shipped.map_tiles.tiles.segment_keyframes, minimal.map_tiles.tiles.segment_keyframes);
  EXPECT_EQ(shipped.map_tiles.tiles.segment_cache_mb, minimal.map_tiles.tiles.segment_cache_mb);
  EXPECT_EQ(shipped.map_tiles.max_keyframes_per_turn, minimal.map_tiles.max_keyframes_per_turn);
  EXPECT_EQ(shipped.map_tiles.cache_mb, minimal.map_tiles.cache_mb);
  EXPECT_EQ(shipped.full_pass.max_duty, minimal.full_pass.max_duty);
  EXPECT_EQ(shipped.full_pass.min_interval_s, minimal.full_pass.min_interval_s);
  EXPECT_EQ(shipped.full_pass.on_stop, minimal.full_pass.on_stop);
  EXPECT_EQ(shipped.standby.strength, minimal.standby.strength);
  expect_same_watchdog(shipped.watchdog, minimal.watchdog);
  EXPECT_EQ(shipped.log_level, minimal.log_level);
}

}  // namespace

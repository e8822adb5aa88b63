// AggregatorConfig from YAML: defaults, every section, and errors naming the key.

#include "litamin2/config/aggregator_config_yaml.hpp"
#include "litamin2/core/config_error.hpp"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

using namespace litamin2;
using namespace litamin2::aggregator;
using service::TransportProfile;

namespace {

void expect_error(const std::string& yaml, const std::string& expected) {
  try {
    aggregator_config_from_yaml(YAML::Load(yaml));
    ADD_FAILURE() << "accepted: " << yaml;
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(AggregatorConfig, DefaultsFromEmptyFile) {
  const AggregatorConfig c = aggregator_config_from_yaml(YAML::Node());
  EXPECT_EQ(c.dds.domain, 0);
  EXPECT_EQ(c.dds.profile, TransportProfile::kLoopback);
  EXPECT_EQ(c.store.path, "/var/lib/litamin2/aggregator.db");
  EXPECT_EQ(c.topics.map_patches, "rt/litamin2/map_patches");
  EXPECT_EQ(c.log_level, "info");
}

TEST(AggregatorConfig, ShippedDefaultLoads) {
  const AggregatorConfig c =
      load_aggregator_config(LITAMIN2_SOURCE_DIR "/config/litamin2-aggregator.yaml");
  EXPECT_EQ(c.dds.profile, TransportProfile::kLoopback);
  EXPECT_EQ(c.dds.domain, 0);
  EXPECT_EQ(c.store.path, "/var/lib/litamin2/aggregator.db");
}

TEST(AggregatorConfig, ReadsEverySection) {
  const AggregatorConfig c = aggregator_config_from_yaml(YAML::Load(R"(
dds: {domain: 7, profile: shm}
topics: {map_patches: rt/x/patches, keyframe_poses: rt/x/poses, map_summary: rt/x/sum, status: rt/x/st}
store: {path: /tmp/a.db, synchronous_full: true, restart_readers: 2, page_size_kb: 4, sqlite_cache_mb: 8}
ingest: {queue_capacity: 10, max_batch: 3, exclusive_odometry: true}
publish: {poses_period_s: 0.5, summary_period_s: 2, summary_max_means: 0, status_period_s: 0.25}
mapper: {map_voxel_size: 2.0, pose_graph: {max_iterations: 7}}
watchdog: {enabled: false, stall_timeout_s: 5}
log_level: debug
)"));
  EXPECT_EQ(c.dds.domain, 7);
  EXPECT_EQ(c.dds.profile, TransportProfile::kShm);
  EXPECT_EQ(c.topics.keyframe_poses, "rt/x/poses");
  EXPECT_TRUE(c.store.synchronous_full);
  EXPECT_EQ(c.store.restart_readers, 2);
  EXPECT_EQ(c.store.page_size_kb, 4);
  EXPECT_EQ(c.store.sqlite_cache_mb, 8);
  EXPECT_EQ(c.ingest.max_batch, 3);
  EXPECT_TRUE(c.ingest.exclusive_odometry);
  EXPECT_EQ(c.publish.summary_max_means, 0);
  EXPECT_DOUBLE_EQ(c.mapper.map_voxel_size, 2.0);
  EXPECT_EQ(c.mapper.graph.max_iterations, 7);
  EXPECT_FALSE(c.watchdog.enabled);
  EXPECT_EQ(c.log_level, "debug");
}

TEST(AggregatorConfig, MapTilesPublishPeriod) {
  EXPECT_DOUBLE_EQ(aggregator_config_from_yaml(YAML::Node()).map_tiles.publish_period_s, 1.0);
  EXPECT_DOUBLE_EQ(aggregator_config_from_yaml(YAML::Load("map_tiles: {publish_period_s: 0.25}"))
                       .map_tiles.publish_period_s,
                   0.25);
  AggregatorConfig c;
  c.map_tiles.publish_period_s = -1.0;
  EXPECT_THROW(validate(c), ConfigError);
}

TEST(AggregatorConfig, MapTilesPersistPeriod) {
  EXPECT_DOUBLE_EQ(aggregator_config_from_yaml(YAML::Node()).map_tiles.persist_period_s, 5.0);
  EXPECT_DOUBLE_EQ(aggregator_config_from_yaml(YAML::Load("map_tiles: {persist_period_s: 0}"))
                       .map_tiles.persist_period_s,
                   0.0);
  AggregatorConfig c;
  c.map_tiles.persist_period_s = -1.0;
  EXPECT_THROW(validate(c), ConfigError);
  c.map_tiles.persist_period_s = 3601.0;
  EXPECT_THROW(validate(c), ConfigError);
  expect_error("map_tiles: {persist_period_s: 7200}",
               "map_tiles.persist_period_s: 7200 is out of range");
}

TEST(AggregatorConfig, ErrorsNameTheKey) {
  expect_error("dds: {domain: 300}", "dds.domain: 300 is out of range");
  expect_error("dds: {profile: tcp}", "dds.profile: 'tcp' is not one of");
  expect_error("dds: {profile: xml}", "dds.xml_file: required");
  expect_error("store: {path: ''}", "store.path: must not be empty");
  expect_error("store: {pth: x}", "store.pth: unknown key");
  expect_error("store: {restart_readers: 0}", "store.restart_readers: 0 is out of range");
  expect_error("store: {sqlite_cache_mb: 0}", "store.sqlite_cache_mb: 0 is out of range");
  expect_error("store: {page_size_kb: 3}", "store.page_size_kb: '3' is not one of");
  expect_error("ingest: {max_batch: 0}", "ingest.max_batch: 0 is out of range");
  expect_error("publish: {status_period_s: abc}", "publish.status_period_s: cannot read 'abc'");
  expect_error("mapper: {map_voxel_size: -1}", "mapper.map_voxel_size: -1 is out of range");
  expect_error("mapper: {pose_graph: {bogus: 1}}", "mapper.pose_graph.bogus: unknown key");
  expect_error("topics: {status: rt/litamin2/map_patches}", "topics: the five topics");
  expect_error("topics: {map_tiles: rt/litamin2/map_summary}", "topics: the five topics");
  expect_error("map_tiles: {tile_size: 0}", "map_tiles.tile_size: 0 is out of range");
  expect_error("map_tiles: {max_keyframes_per_turn: 0}",
               "map_tiles.max_keyframes_per_turn: 0 is out of range");
  expect_error("map_tiles: {tiles: 1}", "map_tiles.tiles: unknown key");
  expect_error("map_tiles: {publish_period_s: -0.5}",
               "map_tiles.publish_period_s: -0.5 is out of range");
  expect_error("map_tiles: {publish_period_s: 7200}",
               "map_tiles.publish_period_s: 7200 is out of range");
  expect_error("map_tiles: {publish_period_s: .nan}", "map_tiles.publish_period_s");
  expect_error("publish: {poses_chunk_keyframes: -1}",
               "publish.poses_chunk_keyframes: -1 is out of range");
  expect_error("topics: {status: 'a b'}", "topics.status: 'a b' is not a valid topic name");
  expect_error("log_level: loud", "log_level: 'loud' is not one of");
  expect_error("colour: red", "colour: unknown key");
}

TEST(AggregatorConfig, StandbyStrength) {
  // 0 (the default): SHARED output writers, as without standby.
  EXPECT_EQ(aggregator_config_from_yaml(YAML::Node()).standby.strength, 0);
  EXPECT_EQ(aggregator_config_from_yaml(YAML::Load("standby: {strength: 2}")).standby.strength, 2);
  expect_error("standby: {strength: -1}", "standby.strength: -1 is out of range");
  expect_error("standby: {strength: 2000000}", "standby.strength: 2000000 is out of range");
  expect_error("standby: {strength: high}", "standby.strength: cannot read 'high'");
  expect_error("standby: {replicas: 2}", "standby.replicas: unknown key");
}

TEST(AggregatorConfig, LimitsAndSecurity) {
  EXPECT_EQ(aggregator_config_from_yaml(YAML::Node()).limits.max_distributions_per_patch, 200'000);
  EXPECT_EQ(aggregator_config_from_yaml(YAML::Load("limits: {max_distributions_per_patch: 7}"))
                .limits.max_distributions_per_patch,
            7);
  expect_error("limits: {max_distributions_per_patch: 0}", "limits.max_distributions_per_patch");
  EXPECT_FALSE(aggregator_config_from_yaml(YAML::Node()).limits.fixed_patch_payloads);
  EXPECT_TRUE(aggregator_config_from_yaml(YAML::Load("limits: {fixed_patch_payloads: true}"))
                  .limits.fixed_patch_payloads);
  expect_error("limits: {fixed_patch_payloads: 3}", "limits.fixed_patch_payloads");
  expect_error("security: {enabled: true}", "security.identity_ca: required");
}

TEST(AggregatorConfig, AMappingAsAKeyAndInfinityAreConfigErrors) {
  // Regression (issue 14): litamin2-aggregator --check-config died with SIGABRT on this.
  expect_error("? {voxel_size: 3}\n", "config: a key must be a name");
  expect_error("mapper: {map_voxel_size: .inf}", "mapper.map_voxel_size: '.inf' is not a finite");
}

TEST(AggregatorConfig, FileErrorsNameTheFile) {
  try {
    load_aggregator_config("/nonexistent/agg.yaml");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/agg.yaml: cannot open"), std::string::npos);
  }
}

TEST(AggregatorConfig, OdometryTopicPatterns) {
  const AggregatorConfig d = aggregator_config_from_yaml(YAML::Node());
  EXPECT_EQ(d.topics.odometry, "rt/*/odom");
  EXPECT_EQ(d.topics.map_odometry, "rt/*/map_odom");
  const AggregatorConfig c = aggregator_config_from_yaml(
      YAML::Load("topics: {odometry: 'rt/fleet/*/odom', map_odometry: 'rt/map/*/pose'}"));
  EXPECT_EQ(c.topics.odometry, "rt/fleet/*/odom");
  EXPECT_EQ(c.topics.map_odometry, "rt/map/*/pose");
  EXPECT_TRUE(
      aggregator_config_from_yaml(YAML::Load("topics: {odometry: ''}")).topics.odometry.empty());
  expect_error("topics: {odometry: 'rt/odom'}", "topics.odometry");
  expect_error("topics: {map_odometry: 'rt/*/*/pose'}", "topics.map_odometry");
  expect_error("topics: {odometry: 'rt/*/x', map_odometry: 'rt/*/x'}", "must be different");
}

TEST(AggregatorConfig, TfAndMapCloudTopics) {
  const AggregatorConfig d = aggregator_config_from_yaml(YAML::Node());
  EXPECT_EQ(d.topics.tf, "rt/tf");
  EXPECT_TRUE(d.topics.map_cloud.empty());  // off unless named
  const AggregatorConfig c =
      aggregator_config_from_yaml(YAML::Load("topics: {tf: '', map_cloud: rt/litamin2/map_cloud}"));
  EXPECT_TRUE(c.topics.tf.empty());
  EXPECT_EQ(c.topics.map_cloud, "rt/litamin2/map_cloud");
  expect_error("topics: {tf: 'rt/a b'}", "topics.tf");
  expect_error("topics: {tf: rt/litamin2/map_summary}", "topics.tf: 'rt/litamin2/map_summary' is");
  expect_error("topics: {map_cloud: rt/tf}", "topics.map_cloud: 'rt/tf' is another topic's");
}

TEST(AggregatorConfig, MetricsListenAndDiagnosticsTopic) {
  const AggregatorConfig defaults = aggregator_config_from_yaml(YAML::Node());
  EXPECT_FALSE(defaults.metrics.enabled());  // off unless asked
  EXPECT_EQ(defaults.topics.diagnostics, "rt/diagnostics");
  const AggregatorConfig on = aggregator_config_from_yaml(
      YAML::Load("metrics: {listen: \"[::1]:9465\"}\ntopics: {diagnostics: ''}"));
  EXPECT_EQ(on.metrics.listen, "[::1]:9465");
  EXPECT_TRUE(on.topics.diagnostics.empty());
  expect_error("metrics: {listen: \"localhost\"}", "metrics.listen");
  expect_error("metrics: {listen: \"localhost:0\"}", "metrics.listen");
  expect_error("metrics: {listen: \"localhost:123456\"}", "metrics.listen");
  expect_error("metrics: {address: x}", "metrics.address");
  expect_error("topics: {diagnostics: rt/litamin2/map_patches}", "topics.diagnostics");
}

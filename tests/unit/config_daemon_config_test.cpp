// Daemon config: the shipped default, every section, tracker overrides, extrinsics, and
// validation errors that name the key and the value.

#include "litamin2/config/daemon_config_yaml.hpp"
#include "litamin2/daemon/stream_frames.hpp"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cstdlib>
#include <fstream>

using namespace litamin2;
using namespace litamin2::daemon;
using service::TransportProfile;

namespace {

DaemonConfig parse(const std::string& text) {
  return daemon_config_from_yaml(YAML::Load(text));
}

/// The ConfigError message of parsing `text` ("" if it parses).
std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(DaemonConfig, ShippedDefaultDiscoversOnLoopback) {
  const DaemonConfig c = load_daemon_config(LITAMIN2_SOURCE_DIR "/config/litamin2d.yaml");
  EXPECT_EQ(c.dds.domain, 0);
  EXPECT_EQ(c.dds.profile, TransportProfile::kLoopback);
  EXPECT_TRUE(c.discovery.enabled);
  EXPECT_EQ(c.discovery.pattern, "rt/*/points");
  EXPECT_TRUE(c.streams.empty());
  EXPECT_EQ(c.queue_depth, 4);
  EXPECT_EQ(c.outputs.status_topic, "rt/litamin2/status");
  EXPECT_EQ(c.log_level, "info");
  // Deskew on (scans with per-point times), the rest of the tracker as config/tracker.yaml.
  EXPECT_TRUE(c.tracker.deskew.enabled);
  EXPECT_EQ(c.tracker.deskew.time_source, TimeSource::kField);
}

TEST(DaemonConfig, FullConfig) {
  const DaemonConfig c = parse(R"(
dds: {domain: 7, profile: shm}
tracker: {voxelizer: {voxel_size: 2.5}, keyframe: {distance: 2}}
streams:
  - id: car1
  - id: car2
    topic: rt/sensors/car2/points
    extrinsic: {xyz: [1, 2, 3], rpy_deg: [0, 0, 90]}
    tracker: {keyframe: {distance: 0.5}}
  - id: fleet/car3
    extrinsic: [1, 0, 0, 0.5,  0, 1, 0, 0,  0, 0, 1, 1.5,  0, 0, 0, 1]
discovery: {enabled: false}
threads: 3
queue_depth: 9
outputs: {odom_suffix: odometry, status_period_s: 0.5, map_patch_history: 50}
watchdog: {enabled: false, stall_timeout_s: 3}
log_level: debug
shutdown_timeout_s: 0.5
)");
  EXPECT_EQ(c.dds.domain, 7);
  EXPECT_EQ(c.dds.profile, TransportProfile::kShm);
  ASSERT_EQ(c.streams.size(), 3u);
  EXPECT_EQ(c.streams[0].topic, "rt/car1/points");
  EXPECT_EQ(c.streams[1].topic, "rt/sensors/car2/points");
  EXPECT_EQ(c.streams[2].topic, "rt/fleet/car3/points");
  // Global tracker section, and the stream's override merged over it key by key.
  EXPECT_EQ(c.tracker.voxelizer.voxel_size, 2.5);
  EXPECT_EQ(c.streams[0].tracker.keyframe.distance, 2.0);
  EXPECT_EQ(c.streams[1].tracker.voxelizer.voxel_size, 2.5);
  EXPECT_EQ(c.streams[1].tracker.keyframe.distance, 0.5);
  EXPECT_EQ(c.streams[1].tracker.keyframe.angle_deg, TrackerConfig().keyframe.angle_deg);
  // Extrinsics.
  EXPECT_TRUE(c.streams[0].extrinsic.matrix().isIdentity());
  EXPECT_TRUE(c.streams[1].extrinsic.translation().isApprox(Eigen::Vector3d(1, 2, 3)));
  EXPECT_TRUE((c.streams[1].extrinsic.linear() * Eigen::Vector3d::UnitX())
                  .isApprox(Eigen::Vector3d::UnitY(), 1e-12));
  EXPECT_TRUE(c.streams[2].extrinsic.translation().isApprox(Eigen::Vector3d(0.5, 0, 1.5)));
  EXPECT_FALSE(c.discovery.enabled);
  EXPECT_EQ(c.threads, 3);
  EXPECT_EQ(c.queue_depth, 9);
  EXPECT_EQ(c.outputs.odom_suffix, "odometry");
  EXPECT_EQ(c.outputs.status_period_s, 0.5);
  EXPECT_EQ(c.outputs.map_patch_history, 50);
  EXPECT_EQ(c.outputs.map_patches_topic, "rt/litamin2/map_patches");
  EXPECT_FALSE(c.watchdog.enabled);
  EXPECT_EQ(c.watchdog.stall_timeout_s, 3.0);
  EXPECT_EQ(c.log_level, "debug");
  EXPECT_EQ(c.shutdown_timeout_s, 0.5);
}

TEST(DaemonConfig, ExtrinsicAsRows) {
  const DaemonConfig c = parse(R"(
streams:
  - id: a
    extrinsic: [[0, -1, 0, 1], [1, 0, 0, 2], [0, 0, 1, 3], [0, 0, 0, 1]]
)");
  EXPECT_TRUE(c.streams[0].extrinsic.translation().isApprox(Eigen::Vector3d(1, 2, 3)));
  EXPECT_EQ(c.streams[0].extrinsic.linear()(0, 1), -1.0);
}

TEST(DaemonConfig, XmlProfile) {
  const std::string xml = ::testing::TempDir() + "/daemon_config_test_profile.xml";
  std::ofstream(xml) << "<dds/>\n";
  const DaemonConfig c = parse("dds: {profile: xml, xml_file: " + xml +
                               ", xml_profile: p}\ndiscovery: {enabled: true}");
  EXPECT_EQ(c.dds.profile, TransportProfile::kXml);
  EXPECT_EQ(c.dds.xml_file, xml);
  EXPECT_EQ(c.dds.xml_profile, "p");
}

TEST(DaemonConfig, ErrorsNameKeyAndValue) {
  const std::string ok = "discovery: {enabled: true}\n";
  EXPECT_EQ(error_of(ok), "");
  EXPECT_EQ(error_of(ok + "threds: 2"), "threds: unknown key");
  EXPECT_EQ(error_of(ok + "threads: many"), "threads: cannot read 'many' as an integer");
  EXPECT_EQ(error_of(ok + "threads: -1"), "threads: -1 is out of range [0, 1024]");
  EXPECT_EQ(error_of(ok + "queue_depth: 0"), "queue_depth: 0 is out of range [1, 10000]");
  EXPECT_EQ(error_of(ok + "dds: {domain: 300}"), "dds.domain: 300 is out of range [0, 232]");
  EXPECT_EQ(error_of(ok + "dds: {profile: udp}"),
            "dds.profile: 'udp' is not one of: loopback, shm, default, xml");
  EXPECT_EQ(error_of(ok + "dds: {profile: xml}"), "dds.xml_file: required when dds.profile is xml");
  EXPECT_EQ(error_of(ok + "dds: {profile: xml, xml_file: /nonexistent.xml, xml_profile: p}"),
            "dds.xml_file: cannot open '/nonexistent.xml'");
  EXPECT_EQ(error_of(ok + "dds: {colour: red}"), "dds.colour: unknown key");
  EXPECT_EQ(error_of(ok + "log_level: loud"),
            "log_level: 'loud' is not one of: trace, debug, info, warn, error, critical, off");
  EXPECT_EQ(error_of("discovery: {enabled: true, pattern: rt/points}"),
            "discovery.pattern: topic pattern 'rt/points' has no '*'");
  EXPECT_EQ(error_of("discovery: {enabled: false}"),
            "streams: no streams configured and discovery.enabled is false");
  EXPECT_EQ(error_of(ok + "tracker: {voxelizer: {voxel_size: big}}"),
            "tracker.voxelizer.voxel_size: cannot read 'big' as a number");
  EXPECT_EQ(error_of(ok + "tracker: {voxeliser: {}}"), "tracker.voxeliser: unknown key");
  EXPECT_EQ(error_of(ok + "outputs: {status_period_s: 0}"),
            "outputs.status_period_s: 0 is out of range [0.01, 3600]");
  EXPECT_EQ(error_of(ok + "outputs: {map_patch_history: 0}"),
            "outputs.map_patch_history: 0 is out of range [1, 1000000]");
  EXPECT_EQ(error_of(ok + "watchdog: {enable: true}"), "watchdog.enable: unknown key");
  EXPECT_EQ(error_of(ok + "streams: {id: a}"),
            "streams: expected a list of streams, got '{id: a}'");
}

TEST(DaemonConfig, StreamErrors) {
  EXPECT_EQ(error_of("streams: [{topic: rt/a/points}]"), "streams[0].id: required");
  EXPECT_EQ(error_of("streams: [{id: 'bad id'}]"),
            "streams[0].id: 'bad id' is not a valid stream id: character ' ' is not allowed (only "
            "letters, digits, '_' and '/')");
  EXPECT_EQ(error_of("streams: [{id: a}, {id: a}]"), "streams[1].id: duplicate stream id 'a'");
  EXPECT_EQ(error_of("streams: [{id: a}, {id: b, topic: rt/a/points}]"),
            "streams[1].topic: 'rt/a/points' is used by another stream");
  EXPECT_EQ(error_of("streams: [{id: a, topic: 'rt/a points'}]"),
            "streams[0].topic: 'rt/a points' is not a valid topic name");
  EXPECT_EQ(error_of("streams: [{id: a, extra: 1}]"), "streams[0].extra: unknown key");
  EXPECT_EQ(error_of("streams: [{id: a, tracker: {map: {radius: -5}}}]")
                .rfind("streams[0].tracker.map.radius", 0),
            0u);
  EXPECT_EQ(error_of("streams: [{id: a, extrinsic: [1, 2, 3]}]"),
            "streams[0].extrinsic: expected 16 numbers (a 4x4 matrix, row-major), got 3");
  EXPECT_EQ(error_of("streams: [{id: a, extrinsic: [2,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]}]"),
            "streams[0].extrinsic: the top-left 3x3 block is not a rotation matrix");
  EXPECT_EQ(error_of("streams: [{id: a, extrinsic: [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,1,1]}]"),
            "streams[0].extrinsic: the last row of the matrix must be 0 0 0 1");
  EXPECT_EQ(error_of("streams: [{id: a, extrinsic: {xyz: [1, 2]}}]"),
            "streams[0].extrinsic.xyz: expected 3 numbers, got 2");
  EXPECT_EQ(error_of("streams: [{id: a, extrinsic: {xyz: [1, 2, x]}}]"),
            "streams[0].extrinsic.xyz[2]: cannot read 'x' as a number");
  EXPECT_EQ(error_of("streams: [{id: a, extrinsic: {rpy: [0, 0, 0], rpy_deg: [0, 0, 0]}}]"),
            "streams[0].extrinsic: give rpy (radians) or rpy_deg, not both");
  EXPECT_EQ(error_of("streams: [{id: a, extrinsic: {quat: [0, 0, 0, 1]}}]"),
            "streams[0].extrinsic.quat: unknown key");
}

TEST(DaemonConfig, StreamOfSeveralTopics) {
  const DaemonConfig c = parse(R"(
streams:
  - id: car1
    topics:
      - topic: rt/car1/front/points
        extrinsic: {xyz: [1.5, 0, 1.8]}
      - topic: rt/car1/rear/points
        extrinsic: {xyz: [-1.0, 0.2, 1.6], rpy_deg: [0, 0, 180]}
    merge_window_s: 0.03
    merge_timeout_s: 0.15
  - id: car2
)");
  ASSERT_EQ(c.streams.size(), 2u);
  const StreamConfig& car1 = c.streams[0];
  EXPECT_TRUE(car1.topic.empty());
  EXPECT_TRUE(car1.extrinsic.matrix().isIdentity(0.0));
  ASSERT_EQ(car1.inputs.size(), 2u);
  EXPECT_EQ(car1.inputs[0].topic, "rt/car1/front/points");
  EXPECT_TRUE(car1.inputs[0].extrinsic.translation().isApprox(Eigen::Vector3d(1.5, 0, 1.8)));
  EXPECT_EQ(car1.inputs[1].topic, "rt/car1/rear/points");
  // Sensor -> base: the rear sensor's x axis points backwards in the base.
  EXPECT_TRUE((car1.inputs[1].extrinsic.linear() * Eigen::Vector3d::UnitX())
                  .isApprox(-Eigen::Vector3d::UnitX(), 1e-12));
  EXPECT_EQ(car1.merge.window_s, 0.03);
  EXPECT_EQ(car1.merge.timeout_s, 0.15);
  // A single-topic stream is as before: its topic, no inputs, the default merge unused.
  EXPECT_EQ(c.streams[1].topic, "rt/car2/points");
  EXPECT_TRUE(c.streams[1].inputs.empty());
  // Defaults of the merge.
  const DaemonConfig d =
      parse("streams: [{id: a, topics: [{topic: rt/a/l/points, extrinsic: {xyz: [0, 0, 1]}}]}]");
  EXPECT_EQ(d.streams[0].merge.window_s, ScanMergerConfig().window_s);
  EXPECT_EQ(d.streams[0].merge.timeout_s, ScanMergerConfig().timeout_s);
}

TEST(DaemonConfig, ZeroCopyTopicIsOptInAndValidated) {
  const DaemonConfig d = parse(
      "streams: [{id: a, zero_copy_topic: rt/a/plain_scan}, {id: b}]\ndiscovery: "
      "{enabled: false}\n");
  EXPECT_EQ(d.streams[0].zero_copy_topic, "rt/a/plain_scan");
  EXPECT_EQ(d.streams[0].topic, "rt/a/points");
  EXPECT_EQ(d.streams[1].zero_copy_topic, "");
  EXPECT_EQ(error_of("streams: [{id: a, zero_copy_topic: ''}]"),
            "streams[0].zero_copy_topic: empty (leave the key out for none)");
  EXPECT_EQ(error_of("streams: [{id: a, zero_copy_topic: 'rt/a plain'}]"),
            "streams[0].zero_copy_topic: 'rt/a plain' is not a valid topic name");
  EXPECT_EQ(error_of("streams: [{id: a, zero_copy_topic: rt/a/points}]"),
            "streams[0].zero_copy_topic: 'rt/a/points' is used by another stream or input");
  EXPECT_EQ(error_of("streams: [{id: a, zero_copy_topic: rt/b/points}, {id: b}]"),
            "streams[1].topic: 'rt/b/points' is used by another stream");
  EXPECT_EQ(error_of("streams: [{id: a, zero_copy_topic: rt/a/z, topics: [{topic: rt/a/front, "
                     "extrinsic: {xyz: [1, 0, 0]}}]}]"),
            "streams[0].zero_copy_topic: only for a stream of one topic");
}

TEST(DaemonConfig, SeveralTopicsErrors) {
  const std::string front = "{topic: rt/a/front, extrinsic: {xyz: [1, 0, 0]}}";
  EXPECT_EQ(error_of("streams: [{id: a, topics: []}]"),
            "streams[0].topics: expected a list of {topic, extrinsic}, got '[]'");
  EXPECT_EQ(error_of("streams: [{id: a, topics: rt/a/front}]"),
            "streams[0].topics: expected a list of {topic, extrinsic}, got 'rt/a/front'");
  EXPECT_EQ(error_of("streams: [{id: a, topic: rt/a/points, topics: [" + front + "]}]"),
            "streams[0].topics: give topic or topics, not both");
  EXPECT_EQ(error_of("streams: [{id: a, topics: [{topic: rt/a/front}]}]"),
            "streams[0].topics[0].extrinsic: required (the sensor's pose in the base frame)");
  EXPECT_EQ(error_of("streams: [{id: a, topics: [{extrinsic: {xyz: [1, 0, 0]}}]}]"),
            "streams[0].topics[0].topic: required");
  EXPECT_EQ(error_of("streams: [{id: a, topics: [{topic: rt/a/front, extrinsic: {xyz: [1, 0, 0]}, "
                     "frame: x}]}]"),
            "streams[0].topics[0].frame: unknown key");
  EXPECT_EQ(error_of("streams: [{id: a, topics: [" + front + ", " + front + "]}]"),
            "streams[0].topics[1].topic: 'rt/a/front' is used by another stream or input");
  EXPECT_EQ(error_of("streams: [{id: b, topic: rt/a/front}, {id: a, topics: [" + front + "]}]"),
            "streams[1].topics[0].topic: 'rt/a/front' is used by another stream or input");
  EXPECT_EQ(error_of("streams: [{id: a, topics: [" + front + "]}, {id: b, topic: rt/a/front}]"),
            "streams[1].topic: 'rt/a/front' is used by another stream");
  EXPECT_EQ(error_of("streams: [{id: a, topics: [{topic: 'rt/a front', extrinsic: {xyz: [1, 0, "
                     "0]}}]}]"),
            "streams[0].topics[0].topic: 'rt/a front' is not a valid topic name");
  EXPECT_EQ(error_of("streams: [{id: a, topics: [{topic: rt/a/front, extrinsic: "
                     "[2,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]}]}]"),
            "streams[0].topics[0].extrinsic: the top-left 3x3 block is not a rotation matrix");
  EXPECT_EQ(error_of("streams: [{id: a, extrinsic: {xyz: [1, 0, 0]}, topics: [" + front + "]}]"),
            "streams[0].extrinsic: a stream with topics gives each topic's extrinsic instead");
  EXPECT_EQ(error_of("streams: [{id: a, topics: [" + front + "], merge_window_s: 0.6}]"),
            "streams[0].merge_window_s: 0.6 is out of range [1e-06, 0.5]");
  EXPECT_EQ(error_of("streams: [{id: a, topics: [" + front + "], merge_timeout_s: 0}]"),
            "streams[0].merge_timeout_s: 0 is out of range [1e-06, 10]");
  EXPECT_EQ(error_of("streams: [{id: a, merge_window_s: 0.05}]"),
            "streams[0]: merge_window_s and merge_timeout_s need topics");
  // The same checks on a config built in code.
  DaemonConfig config;
  config.discovery.enabled = false;
  StreamConfig stream;
  stream.id = "a";
  stream.inputs.push_back({"rt/a/front", Eigen::Isometry3d::Identity()});
  config.streams.push_back(stream);
  EXPECT_NO_THROW(validate(config));
  config.streams[0].inputs[0].extrinsic.linear() *= 1.5;
  EXPECT_THROW(validate(config), ConfigError);
  config.streams[0].inputs[0].extrinsic = Eigen::Isometry3d::Identity();
  config.streams[0].merge.window_s = 0.0;
  EXPECT_THROW(validate(config), ConfigError);
  config.streams[0].merge = ScanMergerConfig();
  config.streams[0].topic = "rt/a/points";
  EXPECT_THROW(validate(config), ConfigError);
}

TEST(DaemonConfig, AMappingAsAKeyIsAConfigErrorEverywhere) {
  // Regression (issue 14): litamin2d --check-config died with SIGABRT on these.
  EXPECT_EQ(error_of("? {voxel_size: 3}\n"), "config: a key must be a name, got '{voxel_size: 3}'");
  EXPECT_EQ(error_of("discovery: {enabled: true}\ntracker:\n  voxelizer:\n    ? voxel_size: 3\n"
                     "    : 2\n"),
            "tracker.voxelizer: a key must be a name, got '{voxel_size: 3}'");
  // A stream's tracker overrides are merged key by key before they are read.
  EXPECT_EQ(error_of("streams: [{id: a, tracker: {? [x]: 1}}]"),
            "streams[0].tracker: a key must be a name, got '[x]'");
}

TEST(DaemonConfig, LimitsAndSecurity) {
  const DaemonConfig defaults = parse("discovery: {enabled: true}");
  EXPECT_EQ(defaults.limits.max_points_per_scan, 5'000'000);
  EXPECT_FALSE(defaults.security.enabled);
  EXPECT_EQ(parse("discovery: {enabled: true}\nlimits: {max_points_per_scan: 1000}")
                .limits.max_points_per_scan,
            1000);
  EXPECT_EQ(error_of("discovery: {enabled: true}\nlimits: {max_points_per_scan: 0}"),
            "limits.max_points_per_scan: 0 is out of range [1, 100000000]");
  EXPECT_EQ(error_of("discovery: {enabled: true}\nsecurity: {enabled: true}"),
            "security.identity_ca: required when security.enabled is true");
  EXPECT_EQ(
      error_of("discovery: {enabled: true}\nsecurity: {enabled: true, identity_ca: /no/ca.pem}"),
      "security.identity_ca: cannot open '/no/ca.pem'");
  EXPECT_EQ(error_of("discovery: {enabled: true}\nsecurity: {certificat: x}"),
            "security.certificat: unknown key");
}

TEST(DaemonConfig, FileErrorsStartWithTheFileName) {
  const std::string path = ::testing::TempDir() + "/daemon_config_test_bad.yaml";
  std::ofstream(path) << "discovery: {enabled: true}\nqueue_depth: -3\n";
  try {
    load_daemon_config(path);
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), path + ": queue_depth: -3 is out of range [1, 10000]");
  }
  EXPECT_THROW(load_daemon_config("/nonexistent/litamin2d.yaml"), ConfigError);
  std::ofstream(path) << "discovery: [unclosed\n";
  EXPECT_THROW(load_daemon_config(path), ConfigError);
}

namespace {

/// Sets ROS_DOMAIN_ID (or unsets it for nullptr) for one scope.
class RosDomainId {
 public:
  explicit RosDomainId(const char* value) {
    if (value)
      setenv("ROS_DOMAIN_ID", value, 1);
    else
      unsetenv("ROS_DOMAIN_ID");
  }
  ~RosDomainId() { unsetenv("ROS_DOMAIN_ID"); }
};

}  // namespace

TEST(DaemonConfig, RosDomainIdWhenTheConfigSetsNoDomain) {
  const std::string no_domain = "dds: {profile: loopback}\nstreams: [{id: car1}]\n";
  const std::string domain_7 = "dds: {domain: 7}\nstreams: [{id: car1}]\n";
  {
    RosDomainId env(nullptr);
    EXPECT_EQ(parse(no_domain).dds.domain, 0);
    EXPECT_EQ(parse(no_domain).dds.domain_source, service::DomainSource::kDefault);
  }
  {
    RosDomainId env("42");
    EXPECT_EQ(parse(no_domain).dds.domain, 42);
    EXPECT_EQ(parse(no_domain).dds.domain_source, service::DomainSource::kEnvironment);
    // A section-less config too; the config's own domain wins.
    EXPECT_EQ(parse("streams: [{id: car1}]\n").dds.domain, 42);
    EXPECT_EQ(parse(domain_7).dds.domain, 7);
    EXPECT_EQ(parse(domain_7).dds.domain_source, service::DomainSource::kConfig);
  }
  {
    RosDomainId env("");  // ROS 2 treats an empty value as unset
    EXPECT_EQ(parse(no_domain).dds.domain, 0);
  }
  for (const char* bad : {"233", "-1", "4x", " 5", "1e2", "0x10", "99999999999"}) {
    RosDomainId env(bad);
    const std::string e = error_of(no_domain);
    EXPECT_NE(e.find("ROS_DOMAIN_ID: '" + std::string(bad) + "' is not a DDS domain id"),
              std::string::npos)
        << bad << ": " << e;
    // Not read when the config sets the domain.
    EXPECT_EQ(parse(domain_7).dds.domain, 7) << bad;
  }
}

TEST(DaemonConfig, FrameNamesAndTheStreamPrefix) {
  const DaemonConfig d = parse("streams: [{id: car1}, {id: car2, sensor_frame: os_sensor}]\n");
  EXPECT_EQ(d.outputs.odom_frame, "odom");
  EXPECT_EQ(d.outputs.base_frame, "base_link");
  EXPECT_TRUE(d.outputs.publish_tf);
  EXPECT_EQ(d.outputs.tf_topic, "rt/tf");
  EXPECT_EQ(d.outputs.tf_static_topic, "rt/tf_static");
  const StreamFrames car1 = stream_frames(d.outputs, d.streams[0]);
  EXPECT_EQ(car1.odom, "car1/odom");
  EXPECT_EQ(car1.base, "car1/base_link");
  EXPECT_EQ(car1.sensor, "car1/lidar");
  EXPECT_EQ(stream_frames(d.outputs, d.streams[1]).sensor, "os_sensor");  // verbatim

  const DaemonConfig plain = parse(R"(
discovery: {enabled: false}
streams: [{id: car1}]
outputs: {frame_prefix: false, odom_frame: odom_lidar, base_frame: base_footprint}
)");
  const StreamFrames f = stream_frames(plain.outputs, plain.streams[0]);
  EXPECT_EQ(f.odom, "odom_lidar");
  EXPECT_EQ(f.base, "base_footprint");
  EXPECT_EQ(f.sensor, "lidar");

  EXPECT_NE(error_of("streams: [{id: a}, {id: b}]\noutputs: {frame_prefix: false}\n")
                .find("outputs.frame_prefix: false needs exactly one configured stream"),
            std::string::npos);
  EXPECT_NE(error_of("discovery: {enabled: true}\noutputs: {frame_prefix: false}\n")
                .find("outputs.frame_prefix"),
            std::string::npos);
  EXPECT_NE(error_of("streams: [{id: a}]\noutputs: {base_frame: /base_link}\n")
                .find("outputs.base_frame: '/base_link' is not a frame name: must not start"),
            std::string::npos);
  EXPECT_NE(error_of("streams: [{id: a, sensor_frame: 'my lidar'}]\n")
                .find("streams[0].sensor_frame: 'my lidar' is not a frame name"),
            std::string::npos);
  EXPECT_NE(error_of("streams: [{id: a}]\noutputs: {odom_frame: x, base_frame: x}\n")
                .find("outputs.base_frame: equals outputs.odom_frame"),
            std::string::npos);
  EXPECT_NE(error_of("streams: [{id: a}]\noutputs: {tf_static_topic: rt/tf}\n")
                .find("outputs.tf_static_topic: equals outputs.tf_topic"),
            std::string::npos);
}

TEST(DaemonConfig, MetricsListenAndDiagnosticsTopic) {
  const DaemonConfig defaults = parse("dds: {domain: 3}");
  EXPECT_FALSE(defaults.metrics.enabled());  // off unless asked
  EXPECT_EQ(defaults.outputs.diagnostics_topic, "rt/diagnostics");
  const DaemonConfig on =
      parse("metrics: {listen: \"127.0.0.1:9464\"}\noutputs: {diagnostics_topic: ''}");
  EXPECT_EQ(on.metrics.listen, "127.0.0.1:9464");
  EXPECT_TRUE(on.outputs.diagnostics_topic.empty());
  for (const char* bad : {"127.0.0.1", "127.0.0.1:0", "127.0.0.1:65536", ":9464"}) {
    const std::string why = error_of(std::string("metrics: {listen: \"") + bad + "\"}");
    EXPECT_NE(why.find("metrics.listen"), std::string::npos) << bad << ": " << why;
  }
  EXPECT_NE(error_of("metrics: {port: 9464}").find("metrics.port"), std::string::npos);
  EXPECT_NE(error_of("outputs: {diagnostics_topic: rt/litamin2/status}")
                .find("outputs.diagnostics_topic"),
            std::string::npos);
}

TEST(DaemonConfig, ShardingAndMemberId) {
  const DaemonConfig defaults = parse("discovery: {enabled: true}\n");
  EXPECT_FALSE(defaults.sharding.enabled);
  EXPECT_TRUE(defaults.member_id.empty());
  EXPECT_FALSE(litamin2::daemon::resolved_member_id(defaults).empty());
  const DaemonConfig c = parse(
      "member_id: host-2\nsharding: {enabled: true, startup_wait_s: 1.5, max_extrapolation_s: "
      "4}\n");
  EXPECT_TRUE(c.sharding.enabled);
  EXPECT_EQ(c.member_id, "host-2");
  EXPECT_EQ(litamin2::daemon::resolved_member_id(c), "host-2");
  EXPECT_EQ(c.sharding.startup_wait_s, 1.5);
  EXPECT_EQ(c.sharding.max_extrapolation_s, 4.0);
  EXPECT_EQ(defaults.sharding.seed_keyframes, 10);
  EXPECT_EQ(defaults.sharding.seed_max_age_s, 10.0);
  const DaemonConfig seeded =
      parse("discovery: {enabled: true}\nsharding: {seed_keyframes: 3, seed_max_age_s: 2.5}\n");
  EXPECT_EQ(seeded.sharding.seed_keyframes, 3);
  EXPECT_EQ(seeded.sharding.seed_max_age_s, 2.5);
  EXPECT_EQ(defaults.sharding.replicas, 1);
  const DaemonConfig standby =
      parse("discovery: {enabled: true}\nsharding: {enabled: true, replicas: 2}\n");
  EXPECT_EQ(standby.sharding.replicas, 2);
}

TEST(DaemonConfig, ShardingErrors) {
  EXPECT_EQ(error_of("member_id: 'a b'\n"),
            "member_id: 'a b' is not a member id: holds a character other than letters, digits, "
            "'.', '_' and '-'");
  EXPECT_EQ(error_of("streams: [{id: a}]\ndiscovery: {enabled: false}\nsharding: {enabled: true}"),
            "sharding.enabled: needs discovery.enabled (only discovered streams move)");
  EXPECT_EQ(error_of("streams: [{id: a}]\nsharding: {enabled: true}"),
            "sharding.enabled: configured streams would be tracked by every daemon; use discovery");
  EXPECT_EQ(error_of("sharding: {enabled: true, startup_wait_s: -1}"),
            "sharding.startup_wait_s: -1 is out of range [0, 600]");
  EXPECT_EQ(error_of("sharding: {enabeld: true}"), "sharding.enabeld: unknown key");
  EXPECT_EQ(error_of("sharding: {seed_keyframes: -1}"),
            "sharding.seed_keyframes: -1 is out of range [0, 1000]");
  EXPECT_EQ(error_of("sharding: {seed_max_age_s: 0}"), "sharding.seed_max_age_s: must be > 0");
  EXPECT_EQ(error_of("sharding: {replicas: 0}"), "sharding.replicas: 0 is out of range [1, 8]");
  EXPECT_EQ(error_of("discovery: {enabled: true}\nsharding: {replicas: 2}"),
            "sharding.replicas: needs sharding.enabled (standbys follow the members)");
}

TEST(DaemonConfig, WorkerSchedulingDefaultsToOtherWithInheritedCpus) {
  const DaemonConfig c = parse("discovery: {enabled: true}");
  EXPECT_EQ(c.scheduling.policy, WorkerPolicy::kOther);
  EXPECT_EQ(c.scheduling.priority, 0);
  EXPECT_TRUE(c.scheduling.cpus.empty());
}

TEST(DaemonConfig, WorkerSchedulingIsRead) {
  const DaemonConfig fifo =
      parse("discovery: {enabled: true}\nscheduling: {policy: fifo, priority: 10, cpus: [1, 0]}");
  EXPECT_EQ(fifo.scheduling.policy, WorkerPolicy::kFifo);
  EXPECT_EQ(fifo.scheduling.priority, 10);
  EXPECT_EQ(fifo.scheduling.cpus, (std::vector<int>{1, 0}));
  const DaemonConfig rr =
      parse("discovery: {enabled: true}\nscheduling: {policy: rr, priority: 99}");
  EXPECT_EQ(rr.scheduling.policy, WorkerPolicy::kRoundRobin);
  EXPECT_EQ(rr.scheduling.priority, 99);
  EXPECT_EQ(fifo.scheduling.scope, SchedulingScope::kWorkers);
  const DaemonConfig process =
      parse("discovery: {enabled: true}\nscheduling: {scope: process, policy: fifo, priority: 10}");
  EXPECT_EQ(process.scheduling.scope, SchedulingScope::kProcess);
  EXPECT_EQ(process.scheduling.policy, WorkerPolicy::kFifo);
  const DaemonConfig pinned = parse("discovery: {enabled: true}\nscheduling: {cpus: [3]}");
  EXPECT_EQ(pinned.scheduling.policy, WorkerPolicy::kOther);
  EXPECT_EQ(pinned.scheduling.cpus, (std::vector<int>{3}));
}

TEST(DaemonConfig, WorkerSchedulingErrors) {
  const std::string head = "discovery: {enabled: true}\n";
  EXPECT_EQ(error_of(head + "scheduling: {policy: deadline, priority: 10}"),
            "scheduling.policy: 'deadline' is not one of: other, fifo, rr");
  EXPECT_EQ(error_of(head + "scheduling: {policy: FIFO, priority: 10}"),
            "scheduling.policy: 'FIFO' is not one of: other, fifo, rr");
  EXPECT_EQ(error_of(head + "scheduling: {scope: all, policy: fifo, priority: 10}"),
            "scheduling.scope: 'all' is not one of: workers, process");
  EXPECT_EQ(error_of(head + "scheduling: {policy: fifo}"),
            "scheduling.priority: 0 is out of range [1, 99] for fifo");
  EXPECT_EQ(error_of(head + "scheduling: {policy: fifo, priority: 100}"),
            "scheduling.priority: 100 is out of range [1, 99] for fifo");
  EXPECT_EQ(error_of(head + "scheduling: {policy: rr, priority: -1}"),
            "scheduling.priority: -1 is out of range [1, 99] for rr");
  EXPECT_EQ(error_of(head + "scheduling: {priority: 10}"),
            "scheduling.priority: 10 given with policy other (a priority is for fifo and rr; other "
            "has none)");
  EXPECT_EQ(error_of(head + "scheduling: {policy: fifo, priority: ten}"),
            "scheduling.priority: cannot read 'ten' as an integer");
  EXPECT_EQ(error_of(head + "scheduling: {cpus: []}"),
            "scheduling.cpus: expected a non-empty list of CPU numbers, got '[]' (leave the key "
            "out for the inherited CPUs)");
  EXPECT_EQ(error_of(head + "scheduling: {cpus: 1}"),
            "scheduling.cpus: expected a non-empty list of CPU numbers, got '1' (leave the key "
            "out for the inherited CPUs)");
  EXPECT_EQ(error_of(head + "scheduling: {cpus: [1, x]}"),
            "scheduling.cpus[1]: cannot read 'x' as a CPU number");
  EXPECT_EQ(error_of(head + "scheduling: {cpus: [1.5]}"),
            "scheduling.cpus[0]: cannot read '1.5' as a CPU number");
  EXPECT_EQ(error_of(head + "scheduling: {cpus: [0, -1]}"),
            "scheduling.cpus[1]: -1 is out of range [0, 1023]");
  EXPECT_EQ(error_of(head + "scheduling: {cpus: [1024]}"),
            "scheduling.cpus[0]: 1024 is out of range [0, 1023]");
  EXPECT_EQ(error_of(head + "scheduling: {cpus: [1, 2, 1]}"),
            "scheduling.cpus[2]: CPU 1 is given twice");
  EXPECT_EQ(error_of(head + "scheduling: {policy: fifo, priority: 10, nice: 5}"),
            "scheduling.nice: unknown key");
  EXPECT_EQ(error_of(head + "scheduling: fifo"),
            "scheduling: expected a mapping of keys to values, got 'fifo'");
}

TEST(DaemonConfig, HeapPrefaultIsAutoANumberOrOff) {
  const std::string discovering = "discovery: {enabled: true}\n";
  // Absent and "auto": 64 MiB and 32 a configured stream, one for a discovering daemon.
  EXPECT_FALSE(parse(discovering).memory.prefault_mb.has_value());
  EXPECT_EQ(prefault_bytes(parse(discovering)), std::size_t{96} << 20);
  const DaemonConfig three = parse(
      "discovery: {enabled: false}\nmemory: {prefault_mb: auto}\n"
      "streams: [{id: a}, {id: b}, {id: c}]\n");
  EXPECT_FALSE(three.memory.prefault_mb.has_value());
  EXPECT_EQ(prefault_auto_mb(three), 64 + 3 * 32);
  EXPECT_EQ(prefault_bytes(three), std::size_t{160} << 20);
  std::string many = "discovery: {enabled: false}\nstreams:\n";
  for (int i = 0; i < 40; ++i) many += "  - {id: s" + std::to_string(i) + "}\n";
  EXPECT_EQ(prefault_auto_mb(parse(many)), 1024);  // 64 + 40 * 32 = 1344, at most 1024
  const DaemonConfig set = parse(discovering + "memory: {prefault_mb: 700}");
  ASSERT_TRUE(set.memory.prefault_mb.has_value());
  EXPECT_EQ(prefault_bytes(set), std::size_t{700} << 20);
  EXPECT_EQ(prefault_bytes(parse(discovering + "memory: {prefault_mb: 0}")), 0u);
  EXPECT_EQ(error_of(discovering + "memory: {prefault_mb: -1}"),
            "memory.prefault_mb: -1 is out of range [0, 65536]");
  EXPECT_EQ(error_of(discovering + "memory: {prefault_mb: 70000}"),
            "memory.prefault_mb: 70000 is out of range [0, 65536]");
  EXPECT_EQ(error_of(discovering + "memory: {prefault_mb: lots}"),
            "memory.prefault_mb: cannot read 'lots' as an integer");
  EXPECT_EQ(error_of(discovering + "memory: {prefault_mb: 1.5}"),
            "memory.prefault_mb: cannot read '1.5' as an integer");
  EXPECT_EQ(error_of(discovering + "memory: {lock: true}"), "memory.lock: unknown key");
  EXPECT_EQ(error_of(discovering + "memory: 5"),
            "memory: expected a mapping of keys to values, got '5'");
}

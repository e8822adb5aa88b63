#include "litamin2/config/daemon_config_yaml.hpp"

#include "litamin2/config/config_file.hpp"
#include "litamin2/config/service_config_yaml.hpp"
#include "litamin2/config/tracker_config_yaml.hpp"
#include "litamin2/config/yaml_section.hpp"
#include "litamin2/core/value_checks.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <optional>

namespace litamin2::daemon {

using config::load_config_file;
using config::read_section;
using config::yaml_text;
using config::YamlSection;

namespace {

/// `over` merged into a copy of `base`: mappings key by key, anything else replaced; `path`
/// names `over` in errors.
YAML::Node merge(const YAML::Node& base, const YAML::Node& over, const std::string& path) {
  if (!over || over.IsNull()) return base ? YAML::Clone(base) : YAML::Node();
  if (!base || !base.IsMap() || !over.IsMap()) return YAML::Clone(over);
  YAML::Node out = YAML::Clone(base);
  for (const auto& entry : over) {
    const std::string key = config::key_name(entry.first, path);
    out[key] = merge(base[key], entry.second, path + "." + key);
  }
  return out;
}

/// Parses a tracker section, naming keys relative to `path` in errors.
TrackerConfig parse_tracker(const YAML::Node& node, const std::string& path) {
  return read_section(path,
                      [&] { return tracker_config_from_yaml(node, daemon_tracker_defaults()); });
}

std::vector<double> numbers(const YAML::Node& node, const std::string& path) {
  std::vector<double> out;
  if (!node.IsSequence()) throw ConfigError(path + ": expected a list of numbers");
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string item = path + "[" + std::to_string(i) + "]";
    if (node[i].IsSequence()) {
      for (double v : numbers(node[i], item)) out.push_back(v);
      continue;
    }
    try {
      out.push_back(node[i].as<double>());
    } catch (const YAML::Exception&) {
      throw ConfigError(item + ": cannot read '" + yaml_text(node[i]) + "' as a number");
    }
    if (!std::isfinite(out.back()))
      throw ConfigError(item + ": " + yaml_text(node[i]) + " is not finite");
  }
  return out;
}

/// A 4x4 matrix (16 numbers, row-major, flat or as 4 rows) or {xyz: [x, y, z], rpy: [r, p, y]}
/// (radians; R = Rz(yaw) Ry(pitch) Rx(roll)) or rpy_deg.
Eigen::Isometry3d parse_extrinsic(const YAML::Node& node, const std::string& path) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  if (node.IsSequence()) {
    const std::vector<double> v = numbers(node, path);
    if (v.size() != 16)
      throw ConfigError(path + ": expected 16 numbers (a 4x4 matrix, row-major), got " +
                        std::to_string(v.size()));
    Eigen::Matrix4d m;
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) m(r, c) = v[r * 4 + c];
    if ((m.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > 1e-9)
      throw ConfigError(path + ": the last row of the matrix must be 0 0 0 1");
    const Eigen::Matrix3d r = m.topLeftCorner<3, 3>();
    if ((r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-6 ||
        r.determinant() < 0)
      throw ConfigError(path + ": the top-left 3x3 block is not a rotation matrix");
    if (const auto why = checks::position_error(m.topRightCorner<3, 1>()))
      throw ConfigError(path + ": the translation " + *why);
    pose.matrix() = m;
    return pose;
  }
  YamlSection s(node, path);
  if (!node.IsMap()) throw ConfigError(path + ": expected a 4x4 matrix or {xyz, rpy}");
  auto vec3 = [&](const std::string& key) -> std::optional<Eigen::Vector3d> {
    const YAML::Node child = s.child(key);
    if (!child) return std::nullopt;
    const std::vector<double> v = numbers(child, s.name(key));
    if (v.size() != 3)
      throw ConfigError(s.name(key) + ": expected 3 numbers, got " + std::to_string(v.size()));
    return Eigen::Vector3d(v[0], v[1], v[2]);
  };
  const auto xyz = vec3("xyz");
  const auto rpy = vec3("rpy");
  const auto rpy_deg = vec3("rpy_deg");
  s.reject_unknown();
  if (rpy && rpy_deg) throw ConfigError(path + ": give rpy (radians) or rpy_deg, not both");
  Eigen::Vector3d angles = rpy       ? *rpy
                           : rpy_deg ? Eigen::Vector3d(*rpy_deg * M_PI / 180.0)
                                     : Eigen::Vector3d::Zero();
  pose.linear() = (Eigen::AngleAxisd(angles.z(), Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(angles.y(), Eigen::Vector3d::UnitY()) *
                   Eigen::AngleAxisd(angles.x(), Eigen::Vector3d::UnitX()))
                      .toRotationMatrix();
  if (xyz) pose.translation() = *xyz;
  if (const auto why = checks::position_error(pose.translation()))
    throw ConfigError(path + ".xyz: " + *why);
  return pose;
}

/// A non-empty list of CPU numbers (integers); their range and duplicates are checked by
/// validate().
std::vector<int> cpu_list(const YAML::Node& node, const std::string& path) {
  if (!node.IsSequence() || node.size() == 0)
    throw ConfigError(path + ": expected a non-empty list of CPU numbers, got '" + yaml_text(node) +
                      "' (leave the key out for the inherited CPUs)");
  std::vector<int> out;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string item = path + "[" + std::to_string(i) + "]";
    try {
      if (!node[i].IsScalar()) throw YAML::Exception(YAML::Mark(), "not a scalar");
      out.push_back(node[i].as<int>());
    } catch (const YAML::Exception&) {
      throw ConfigError(item + ": cannot read '" + yaml_text(node[i]) + "' as a CPU number");
    }
  }
  return out;
}

/// A stream's `topics:`: a list of {topic, extrinsic}, at least one; both keys required.
std::vector<SensorInput> parse_inputs(const YAML::Node& node, const std::string& path) {
  if (!node.IsSequence() || node.size() == 0)
    throw ConfigError(path + ": expected a list of {topic, extrinsic}, got '" + yaml_text(node) +
                      "'");
  std::vector<SensorInput> inputs;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string item = path + "[" + std::to_string(i) + "]";
    if (!node[i].IsMap()) throw ConfigError(item + ": expected a mapping {topic, extrinsic}");
    YamlSection s(node[i], item);
    SensorInput input;
    if (!s.read("topic", input.topic)) throw ConfigError(item + ".topic: required");
    const YAML::Node extrinsic = s.child("extrinsic");
    if (!extrinsic || extrinsic.IsNull())
      throw ConfigError(item + ".extrinsic: required (the sensor's pose in the base frame)");
    input.extrinsic = parse_extrinsic(extrinsic, item + ".extrinsic");
    s.reject_unknown();
    inputs.push_back(std::move(input));
  }
  return inputs;
}

}  // namespace

DaemonConfig daemon_config_from_yaml(const YAML::Node& node) {
  DaemonConfig config;
  if (!node || node.IsNull()) throw ConfigError("config: empty; give streams or discovery");
  YamlSection root(node, "");

  config.dds = service::transport_config_from_yaml(root.child("dds"));
  config.security = service::security_config_from_yaml(root.child("security"));
  {
    YamlSection limits(root.child("limits"), "limits");
    limits.read_range("max_points_per_scan", config.limits.max_points_per_scan, 1, 100'000'000);
    limits.reject_unknown();
  }

  // tracker (global); kept as YAML so streams can override single keys.
  const YAML::Node tracker_node = root.child("tracker");
  config.tracker = parse_tracker(tracker_node, "tracker");

  {
    YamlSection discovery(root.child("discovery"), "discovery");
    discovery.read("enabled", config.discovery.enabled);
    discovery.read("pattern", config.discovery.pattern);
    discovery.read_range("max_streams", config.discovery.max_streams, 1, 4096);
    discovery.reject_unknown();
  }
  root.read("member_id", config.member_id);
  {
    YamlSection sharding(root.child("sharding"), "sharding");
    sharding.read("enabled", config.sharding.enabled);
    sharding.read_range("startup_wait_s", config.sharding.startup_wait_s, 0.0, 600.0);
    sharding.read_range("max_extrapolation_s", config.sharding.max_extrapolation_s, 0.0, 600.0);
    sharding.read_range("seed_keyframes", config.sharding.seed_keyframes, 0, 1000);
    sharding.read_range("seed_max_age_s", config.sharding.seed_max_age_s, 0.0, 3600.0);
    sharding.read_range("replicas", config.sharding.replicas, 1, 8);
    sharding.reject_unknown();
  }

  const YAML::Node streams = root.child("streams");
  if (streams && !streams.IsNull()) {
    if (!streams.IsSequence())
      throw ConfigError("streams: expected a list of streams, got '" + yaml_text(streams) + "'");
    for (std::size_t i = 0; i < streams.size(); ++i) {
      const std::string path = "streams[" + std::to_string(i) + "]";
      if (!streams[i].IsMap()) throw ConfigError(path + ": expected a mapping with at least an id");
      YamlSection s(streams[i], path);
      StreamConfig stream;
      if (!s.read("id", stream.id)) throw ConfigError(path + ".id: required");
      const bool has_topic = s.read("topic", stream.topic);
      const YAML::Node topics = s.child("topics");
      if (topics && !topics.IsNull()) {
        if (has_topic) throw ConfigError(path + ".topics: give topic or topics, not both");
        stream.inputs = parse_inputs(topics, path + ".topics");
        s.read_range("merge_window_s", stream.merge.window_s, 1e-6, 0.5);
        s.read_range("merge_timeout_s", stream.merge.timeout_s, 1e-6, 10.0);
      } else {
        if (!has_topic) stream.topic = "rt/" + stream.id + "/points";
        if (s.child("merge_window_s") || s.child("merge_timeout_s"))
          throw ConfigError(path + ": merge_window_s and merge_timeout_s need topics");
      }
      s.read("sensor_frame", stream.sensor_frame);
      if (s.read("zero_copy_topic", stream.zero_copy_topic) && stream.zero_copy_topic.empty())
        throw ConfigError(path + ".zero_copy_topic: empty (leave the key out for none)");
      const YAML::Node extrinsic = s.child("extrinsic");
      if (extrinsic && !extrinsic.IsNull()) {
        if (!stream.inputs.empty())
          throw ConfigError(
              path + ".extrinsic: a stream with topics gives each topic's extrinsic instead");
        stream.extrinsic = parse_extrinsic(extrinsic, path + ".extrinsic");
      }
      const YAML::Node overrides = s.child("tracker");
      if (overrides && !overrides.IsNull() && !overrides.IsMap())
        throw ConfigError(path + ".tracker: expected a mapping of tracker keys");
      stream.tracker =
          parse_tracker(merge(tracker_node, overrides, path + ".tracker"), path + ".tracker");
      s.reject_unknown();
      config.streams.push_back(std::move(stream));
    }
  }

  root.read_range("threads", config.threads, 0, 1024);
  root.read_range("queue_depth", config.queue_depth, 1, 10000);
  {
    YamlSection scheduling(root.child("scheduling"), "scheduling");
    scheduling.read_enum(
        "scope", config.scheduling.scope,
        {{"workers", SchedulingScope::kWorkers}, {"process", SchedulingScope::kProcess}});
    scheduling.read_enum("policy", config.scheduling.policy,
                         {{"other", WorkerPolicy::kOther},
                          {"fifo", WorkerPolicy::kFifo},
                          {"rr", WorkerPolicy::kRoundRobin}});
    scheduling.read("priority", config.scheduling.priority);
    const YAML::Node cpus = scheduling.child("cpus");
    if (cpus && !cpus.IsNull()) config.scheduling.cpus = cpu_list(cpus, "scheduling.cpus");
    scheduling.reject_unknown();
  }
  root.read_range("shutdown_timeout_s", config.shutdown_timeout_s, 0.0, 60.0);
  {
    YamlSection memory(root.child("memory"), "memory");
    const YAML::Node prefault = memory.child("prefault_mb");
    if (prefault && prefault.IsScalar() && prefault.Scalar() == "auto") {
      config.memory.prefault_mb.reset();
    } else {
      int mib = 0;
      if (memory.read("prefault_mb", mib)) config.memory.prefault_mb = mib;
    }
    memory.reject_unknown();
  }

  {
    YamlSection outputs(root.child("outputs"), "outputs");
    outputs.read("odom_suffix", config.outputs.odom_suffix);
    outputs.read("map_patches_topic", config.outputs.map_patches_topic);
    outputs.read("status_topic", config.outputs.status_topic);
    outputs.read("diagnostics_topic", config.outputs.diagnostics_topic);
    outputs.read_range("status_period_s", config.outputs.status_period_s, 0.01, 3600.0);
    outputs.read_range("map_patch_history", config.outputs.map_patch_history, 1, 1'000'000);
    outputs.read("odom_frame", config.outputs.odom_frame);
    outputs.read("base_frame", config.outputs.base_frame);
    outputs.read("sensor_frame", config.outputs.sensor_frame);
    outputs.read("frame_prefix", config.outputs.frame_prefix);
    outputs.read("publish_tf", config.outputs.publish_tf);
    outputs.read("tf_topic", config.outputs.tf_topic);
    outputs.read("tf_static_topic", config.outputs.tf_static_topic);
    outputs.reject_unknown();
  }

  config.watchdog =
      service::watchdog_config_from_yaml(root.child("watchdog"), 3600.0, config.watchdog);
  config.metrics = service::metrics_config_from_yaml(root.child("metrics"));
  service::read_log_level(root, config.log_level);
  root.reject_unknown();
  validate(config);
  return config;
}

DaemonConfig load_daemon_config(const std::string& path) {
  return load_config_file(path, daemon_config_from_yaml);
}

}  // namespace litamin2::daemon

#include "litamin2/daemon/daemon_config.hpp"

#include "litamin2/core/yaml_section.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

namespace litamin2::daemon {
namespace {

/// `over` merged into a copy of `base`: mappings key by key, anything else replaced.
YAML::Node merge(const YAML::Node& base, const YAML::Node& over) {
  if (!over || over.IsNull()) return base ? YAML::Clone(base) : YAML::Node();
  if (!base || !base.IsMap() || !over.IsMap()) return YAML::Clone(over);
  YAML::Node out = YAML::Clone(base);
  for (const auto& entry : over) {
    const std::string key = entry.first.as<std::string>();
    out[key] = merge(base[key], entry.second);
  }
  return out;
}

/// Parses a tracker section, naming keys relative to `path` in errors.
TrackerConfig parse_tracker(const YAML::Node& node, const std::string& path) {
  try {
    return tracker_config_from_yaml(node);
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    if (what.rfind("config:", 0) == 0) throw ConfigError(path + what.substr(6));
    throw ConfigError(path + "." + what);
  }
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
  return pose;
}

/// DDS topic names: no spaces or control characters, no leading '/'.
void check_topic(const std::string& topic, const std::string& path) {
  if (topic.empty()) throw ConfigError(path + ": empty topic name");
  for (char c : topic)
    if (static_cast<unsigned char>(c) <= ' ' || c == '*' || c == '?')
      throw ConfigError(path + ": '" + topic + "' is not a valid topic name");
}

}  // namespace

const char* to_string(TransportProfile profile) {
  switch (profile) {
    case TransportProfile::loopback:
      return "loopback";
    case TransportProfile::shm:
      return "shm";
    case TransportProfile::default_profile:
      return "default";
    case TransportProfile::xml:
      return "xml";
  }
  return "?";
}

bool is_valid_stream_id(const std::string& id) {
  // ROS 2 name rules for a relative namespace (as litamin2::dds::stream_id_error checks them):
  // tokens of letters, digits and '_' separated by single '/', no token starting with a digit,
  // no "__", at most 245 characters so that every topic of the stream stays within 255.
  if (id.empty() || id.size() > 245 || id.find("__") != std::string::npos) return false;
  std::size_t token_start = 0;
  for (std::size_t i = 0; i <= id.size(); ++i) {
    if (i == id.size() || id[i] == '/') {
      if (i == token_start) return false;  // empty token: leading, trailing or double '/'
      if (id[token_start] >= '0' && id[token_start] <= '9') return false;
      token_start = i + 1;
      continue;
    }
    const char c = id[i];
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_'))
      return false;
  }
  return true;
}

std::optional<std::string> match_topic_pattern(const std::string& pattern,
                                               const std::string& topic) {
  const auto star = pattern.find('*');
  if (star == std::string::npos) return std::nullopt;
  const std::string prefix = pattern.substr(0, star), suffix = pattern.substr(star + 1);
  if (topic.size() <= prefix.size() + suffix.size()) return std::nullopt;
  if (topic.compare(0, prefix.size(), prefix) != 0) return std::nullopt;
  if (topic.compare(topic.size() - suffix.size(), suffix.size(), suffix) != 0) return std::nullopt;
  std::string id = topic.substr(prefix.size(), topic.size() - prefix.size() - suffix.size());
  if (!is_valid_stream_id(id)) return std::nullopt;
  return id;
}

StreamConfig discovered_stream(const DaemonConfig& config, const std::string& id,
                               const std::string& topic) {
  StreamConfig stream;
  stream.id = id;
  stream.topic = topic;
  stream.tracker = config.tracker;
  return stream;
}

DdsConfig dds_config_from_yaml(const YAML::Node& node) {
  DdsConfig config;
  YamlSection dds(node, "dds");
  dds.read_range("domain", config.domain, 0, 232);
  dds.read_enum<TransportProfile>("profile", config.profile,
                                  {{"loopback", TransportProfile::loopback},
                                   {"shm", TransportProfile::shm},
                                   {"default", TransportProfile::default_profile},
                                   {"xml", TransportProfile::xml}});
  dds.read("xml_file", config.xml_file);
  dds.read("xml_profile", config.xml_profile);
  dds.reject_unknown();
  if (config.profile == TransportProfile::xml) {
    if (config.xml_file.empty())
      throw ConfigError("dds.xml_file: required when dds.profile is xml");
    if (config.xml_profile.empty())
      throw ConfigError("dds.xml_profile: required when dds.profile is xml");
    if (!std::ifstream(config.xml_file))
      throw ConfigError("dds.xml_file: cannot open '" + config.xml_file + "'");
  } else if (!config.xml_file.empty() || !config.xml_profile.empty()) {
    throw ConfigError("dds.xml_file: only used with dds.profile: xml (profile is " +
                      std::string(to_string(config.profile)) + ")");
  }
  return config;
}

DaemonConfig daemon_config_from_yaml(const YAML::Node& node) {
  DaemonConfig config;
  if (!node || node.IsNull()) throw ConfigError("config: empty; give streams or discovery");
  YamlSection root(node, "");

  config.dds = dds_config_from_yaml(root.child("dds"));

  // tracker (global); kept as YAML so streams can override single keys.
  const YAML::Node tracker_node = root.child("tracker");
  config.tracker = parse_tracker(tracker_node, "tracker");

  // discovery
  {
    YamlSection discovery(root.child("discovery"), "discovery");
    discovery.read("enabled", config.discovery.enabled);
    discovery.read("pattern", config.discovery.pattern);
    discovery.read_range("max_streams", config.discovery.max_streams, 1, 4096);
    discovery.reject_unknown();
    const std::string& p = config.discovery.pattern;
    if (std::count(p.begin(), p.end(), '*') != 1)
      throw ConfigError("discovery.pattern: '" + p + "' must contain exactly one '*'");
  }

  // streams
  const YAML::Node streams = root.child("streams");
  if (streams && !streams.IsNull()) {
    if (!streams.IsSequence())
      throw ConfigError("streams: expected a list of streams, got '" + yaml_text(streams) + "'");
    std::set<std::string> ids, topics;
    for (std::size_t i = 0; i < streams.size(); ++i) {
      const std::string path = "streams[" + std::to_string(i) + "]";
      if (!streams[i].IsMap()) throw ConfigError(path + ": expected a mapping with at least an id");
      YamlSection s(streams[i], path);
      StreamConfig stream;
      if (!s.read("id", stream.id)) throw ConfigError(path + ".id: required");
      if (!is_valid_stream_id(stream.id))
        throw ConfigError(
            path + ".id: '" + stream.id +
            "' is not a valid stream id (ROS name tokens: letters, digits, _; separated by /)");
      if (!ids.insert(stream.id).second)
        throw ConfigError(path + ".id: duplicate stream id '" + stream.id + "'");
      if (!s.read("topic", stream.topic)) stream.topic = "rt/" + stream.id + "/points";
      check_topic(stream.topic, path + ".topic");
      if (!topics.insert(stream.topic).second)
        throw ConfigError(path + ".topic: '" + stream.topic + "' is used by another stream");
      const YAML::Node extrinsic = s.child("extrinsic");
      if (extrinsic && !extrinsic.IsNull())
        stream.extrinsic = parse_extrinsic(extrinsic, path + ".extrinsic");
      const YAML::Node overrides = s.child("tracker");
      if (overrides && !overrides.IsNull() && !overrides.IsMap())
        throw ConfigError(path + ".tracker: expected a mapping of tracker keys");
      stream.tracker = parse_tracker(merge(tracker_node, overrides), path + ".tracker");
      s.reject_unknown();
      config.streams.push_back(std::move(stream));
    }
  }

  root.read_range("threads", config.threads, 0, 1024);
  root.read_range("queue_depth", config.queue_depth, 1, 10000);
  root.read_range("shutdown_timeout_s", config.shutdown_timeout_s, 0.0, 60.0);

  // outputs
  {
    YamlSection outputs(root.child("outputs"), "outputs");
    outputs.read("odom_suffix", config.outputs.odom_suffix);
    outputs.read("map_patches_topic", config.outputs.map_patches_topic);
    outputs.read("status_topic", config.outputs.status_topic);
    outputs.read_range("status_period_s", config.outputs.status_period_s, 0.01, 3600.0);
    outputs.read_range("map_patch_history", config.outputs.map_patch_history, 1, 1'000'000);
    outputs.read("odom_frame", config.outputs.odom_frame);
    outputs.reject_unknown();
    check_topic(config.outputs.odom_suffix, "outputs.odom_suffix");
    check_topic(config.outputs.map_patches_topic, "outputs.map_patches_topic");
    check_topic(config.outputs.status_topic, "outputs.status_topic");
    if (config.outputs.odom_frame.empty())
      throw ConfigError("outputs.odom_frame: must not be empty");
  }

  // watchdog
  {
    YamlSection watchdog(root.child("watchdog"), "watchdog");
    watchdog.read("enabled", config.watchdog.enabled);
    watchdog.read_range("stall_timeout_s", config.watchdog.stall_timeout_s, 0.1, 3600.0);
    watchdog.reject_unknown();
  }

  if (root.read("log_level", config.log_level)) {
    static const std::set<std::string> levels = {"trace", "debug",    "info", "warn",
                                                 "error", "critical", "off"};
    if (!levels.count(config.log_level))
      throw ConfigError("log_level: '" + config.log_level +
                        "' is not one of: trace, debug, info, warn, error, critical, off");
  }

  root.reject_unknown();
  if (config.streams.empty() && !config.discovery.enabled)
    throw ConfigError("streams: no streams configured and discovery.enabled is false");
  return config;
}

DaemonConfig load_daemon_config(const std::string& path) {
  YAML::Node node;
  if (!std::ifstream(path)) throw ConfigError(path + ": cannot open the config file");
  try {
    node = YAML::LoadFile(path);
  } catch (const YAML::Exception& e) {
    throw ConfigError(path + ": not valid YAML: " + e.what());
  }
  try {
    return daemon_config_from_yaml(node);
  } catch (const ConfigError& e) {
    throw ConfigError(path + ": " + e.what());
  }
}

}  // namespace litamin2::daemon

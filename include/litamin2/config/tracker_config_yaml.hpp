#pragma once
/// The tracker's config (TrackerConfig) from and to YAML: the `tracker:` section of
/// litamin2d.yaml and the files of `litamin2-odometry --config` (config/tracker.yaml).

#include "litamin2/core/tracker_config.hpp"

#include <yaml-cpp/yaml.h>

#include <string>

namespace litamin2 {

/// Reads a tracker config from a YAML mapping; absent keys keep their defaults, unknown keys
/// and invalid values (validate(TrackerConfig)) throw ConfigError naming the key.
TrackerConfig tracker_config_from_yaml(const YAML::Node& node);
/// As above, with the absent keys taken from `base` (e.g. litamin2d's tracker defaults).
TrackerConfig tracker_config_from_yaml(const YAML::Node& node, const TrackerConfig& base);
/// Reads a YAML file (the whole file, or its `tracker:` section if it has one).
TrackerConfig load_tracker_config(const std::string& path);
/// The full config as YAML (every key, so a run's config.yaml reproduces it).
std::string tracker_config_to_yaml(const TrackerConfig& config);

}  // namespace litamin2

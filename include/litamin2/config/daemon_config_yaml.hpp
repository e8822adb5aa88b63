#pragma once
/// litamin2d.yaml: the daemon's config (DaemonConfig) from YAML.

#include "litamin2/daemon/daemon_config.hpp"

#include <yaml-cpp/yaml.h>

#include <string>

namespace litamin2::daemon {

/// Reads a daemon config from a YAML mapping. Absent keys keep their defaults; unknown keys,
/// values of the wrong type or out of range, and configs that fail daemon::validate throw
/// ConfigError naming the key and the value. A stream's `tracker:` section is merged key by
/// key over the global one; its `extrinsic` is a 4x4 matrix (16 numbers, row-major, flat or as
/// 4 rows) or {xyz: [x, y, z], rpy: [r, p, y]} (radians; R = Rz(yaw) Ry(pitch) Rx(roll)) or
/// rpy_deg.
DaemonConfig daemon_config_from_yaml(const YAML::Node& node);
/// Reads a YAML file; error messages start with the file name.
DaemonConfig load_daemon_config(const std::string& path);

}  // namespace litamin2::daemon

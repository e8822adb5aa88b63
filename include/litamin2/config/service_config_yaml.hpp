#pragma once
/// The sections both processes' configs share: `dds:` (TransportConfig), `security:`
/// (SecurityConfig), `watchdog:` (WatchdogConfig), `metrics:` (MetricsConfig) and `log_level`.

#include "litamin2/config/yaml_section.hpp"
#include "litamin2/service/metrics_config.hpp"
#include "litamin2/service/security_config.hpp"
#include "litamin2/service/transport_config.hpp"
#include "litamin2/service/watchdog_config.hpp"

#include <yaml-cpp/yaml.h>

#include <string>

namespace litamin2::service {

/// Reads a `dds:` section (a null node gives the defaults); errors name keys as dds.<key>. An
/// xml profile needs a readable xml_file and an xml_profile; other profiles take neither.
/// Without a `domain` key the domain is ROS_DOMAIN_ID's (as a ROS 2 node's), else 0; an
/// invalid ROS_DOMAIN_ID is then a ConfigError naming it (it is not read when the key is set).
TransportConfig transport_config_from_yaml(const YAML::Node& node);

/// Reads a `security:` section (a null node: security off); errors name keys as security.<key>.
/// When enabled, each of the six files must be given and readable (security_config_error).
SecurityConfig security_config_from_yaml(const YAML::Node& node);

/// Reads a `watchdog:` section over `defaults` (the process's own); stall_timeout_s must lie in
/// [0.1, max_stall_timeout_s].
WatchdogConfig watchdog_config_from_yaml(const YAML::Node& node, double max_stall_timeout_s,
                                         const WatchdogConfig& defaults);

/// Reads a `metrics:` section (a null node: off); errors name keys as metrics.<key>. A
/// non-empty listen must be HOST:PORT with a port in 1..65535 (metrics_config_error).
MetricsConfig metrics_config_from_yaml(const YAML::Node& node);

/// Reads the `log_level` key of `section` into `level` (one of kLogLevels).
void read_log_level(config::YamlSection& section, std::string& level);

}  // namespace litamin2::service

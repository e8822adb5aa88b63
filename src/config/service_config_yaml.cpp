#include "litamin2/config/service_config_yaml.hpp"

#include "litamin2/service/logging.hpp"

#include <cstdlib>
#include <fstream>
#include <utility>
#include <vector>

namespace litamin2::service {

using config::YamlSection;

TransportConfig transport_config_from_yaml(const YAML::Node& node) {
  TransportConfig config;
  YamlSection dds(node, "dds");
  const YAML::Node domain = dds.child("domain");
  if (domain && !domain.IsNull()) {
    dds.read_range("domain", config.domain, 0, 232);
    config.domain_source = DomainSource::kConfig;
  } else {
    // As a ROS 2 node: the environment's domain when the config names none.
    std::string error;
    const char* env = std::getenv("ROS_DOMAIN_ID");
    if (const auto id = parse_ros_domain_id(env, &error)) {
      config.domain = *id;
      config.domain_source = DomainSource::kEnvironment;
    } else if (!error.empty()) {
      throw ConfigError(error + " (dds.domain is not set, so litamin2 reads it)");
    }
  }
  dds.read_enum<TransportProfile>("profile", config.profile,
                                  {{"loopback", TransportProfile::kLoopback},
                                   {"shm", TransportProfile::kShm},
                                   {"default", TransportProfile::kDefault},
                                   {"xml", TransportProfile::kXml}});
  dds.read("xml_file", config.xml_file);
  dds.read("xml_profile", config.xml_profile);
  dds.reject_unknown();
  if (config.profile == TransportProfile::kXml) {
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

SecurityConfig security_config_from_yaml(const YAML::Node& node) {
  SecurityConfig config;
  YamlSection security(node, "security");
  security.read("enabled", config.enabled);
  for (const auto& [key, member] : SecurityConfig::kFiles) security.read(key, config.*member);
  security.reject_unknown();
  if (const auto why = security_config_error(config)) throw ConfigError(*why);
  return config;
}

WatchdogConfig watchdog_config_from_yaml(const YAML::Node& node, double max_stall_timeout_s,
                                         const WatchdogConfig& defaults) {
  WatchdogConfig config = defaults;
  YamlSection watchdog(node, "watchdog");
  watchdog.read("enabled", config.enabled);
  watchdog.read_range("stall_timeout_s", config.stall_timeout_s, 0.1, max_stall_timeout_s);
  watchdog.reject_unknown();
  return config;
}

MetricsConfig metrics_config_from_yaml(const YAML::Node& node) {
  MetricsConfig config;
  YamlSection metrics(node, "metrics");
  metrics.read("listen", config.listen);
  metrics.reject_unknown();
  if (const auto why = metrics_config_error(config)) throw ConfigError(*why);
  return config;
}

void read_log_level(YamlSection& section, std::string& level) {
  std::vector<std::pair<std::string, std::string>> names;
  for (const char* name : kLogLevels) names.emplace_back(name, name);
  section.read_enum<std::string>("log_level", level, names);
}

}  // namespace litamin2::service

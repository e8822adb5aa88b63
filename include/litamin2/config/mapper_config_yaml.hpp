#pragma once
/// The mapping back end's config (MapperConfig) from and to YAML: the `mapper:` section
/// of litamin2-aggregator.yaml and the files of `litamin2-odometry --mapper-config`
/// (config/mapper.yaml).

#include "litamin2/mapping/mapper_config.hpp"

#include <yaml-cpp/yaml.h>

#include <string>

namespace litamin2::mapping {

/// Reads a mapper config from a YAML mapping; absent keys keep their defaults, unknown keys
/// and out-of-range values throw ConfigError naming the key and value.
MapperConfig mapper_config_from_yaml(const YAML::Node& node);
/// Reads a YAML file (the whole file, or its `mapper:` section if it has one); errors name the
/// file.
MapperConfig load_mapper_config(const std::string& path);
/// The full config as YAML (every key).
std::string mapper_config_to_yaml(const MapperConfig& config);

}  // namespace litamin2::mapping

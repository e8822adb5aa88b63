#pragma once
/// litamin2-aggregator.yaml: the aggregator's config (AggregatorConfig) from YAML.

#include "litamin2/aggregator/aggregator_config.hpp"

#include <yaml-cpp/yaml.h>

#include <string>

namespace litamin2::aggregator {

/// Reads an aggregator config from a YAML mapping (an empty or null node gives the defaults).
/// Unknown keys, values of the wrong type or out of range, and configs that fail
/// aggregator::validate throw ConfigError naming the key (as a dotted path) and the value.
AggregatorConfig aggregator_config_from_yaml(const YAML::Node& node);
/// Reads a YAML file; error messages start with the file name.
AggregatorConfig load_aggregator_config(const std::string& path);

}  // namespace litamin2::aggregator

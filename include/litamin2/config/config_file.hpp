#pragma once
/// The one way a config file is read: its YAML, a reader for the root node, and error messages
/// that start with the file's name and name the key as a dotted path.

#include "litamin2/core/config_error.hpp"

#include <yaml-cpp/yaml.h>

#include <string>

namespace litamin2::config {

/// The YAML of a file. A file that cannot be opened and text that is not YAML are ConfigErrors
/// naming the file.
YAML::Node load_yaml_file(const std::string& path);

/// `read(node)` on the YAML of the file `path`; a ConfigError or yaml-cpp exception from the
/// reader becomes a ConfigError "<path>: <message>".
template <class Read>
auto load_config_file(const std::string& path, Read read) -> decltype(read(YAML::Node())) {
  const YAML::Node node = load_yaml_file(path);
  try {
    return read(node);
  } catch (const ConfigError& e) {
    throw ConfigError(path + ": " + e.what());
  } catch (const YAML::Exception& e) {
    throw ConfigError(path + ": " + e.what());
  }
}

/// A ConfigError of a reader that names keys relative to its own root ("voxel_size: ...", or
/// "config: ..." for the root itself) moved under `section` ("tracker.voxel_size: ...").
ConfigError in_section(const std::string& section, const ConfigError& error);

/// `read()` of a nested section whose reader names keys relative to the section.
template <class Read>
auto read_section(const std::string& section, Read read) -> decltype(read()) {
  try {
    return read();
  } catch (const ConfigError& e) {
    throw in_section(section, e);
  }
}

}  // namespace litamin2::config

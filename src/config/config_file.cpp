#include "litamin2/config/config_file.hpp"

#include <fstream>

namespace litamin2::config {

YAML::Node load_yaml_file(const std::string& path) {
  if (!std::ifstream(path)) throw ConfigError(path + ": cannot open the config file");
  try {
    return YAML::LoadFile(path);
  } catch (const YAML::Exception& e) {
    throw ConfigError(path + ": not valid YAML: " + e.what());
  }
}

ConfigError in_section(const std::string& section, const ConfigError& error) {
  const std::string what = error.what();
  if (what.rfind("config:", 0) == 0) return ConfigError(section + what.substr(6));
  return ConfigError(section + "." + what);
}

}  // namespace litamin2::config

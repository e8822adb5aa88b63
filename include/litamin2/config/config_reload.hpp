#pragma once
/// SIGHUP for a running service: its config file is read again and validated by the service's
/// own loader. What can change at run time (today: the log level) is applied; every other
/// top-level key whose YAML changed is reported as needing a restart and left as it runs. An
/// invalid file changes nothing.

#include <yaml-cpp/yaml.h>

#include <functional>
#include <string>
#include <vector>

namespace litamin2::config {

/// The top-level keys added, removed or changed between two YAML documents (compared by their
/// emitted YAML), sorted. A document that is not a map counts as an empty map.
std::vector<std::string> changed_top_level_keys(const YAML::Node& before, const YAML::Node& after);

class ConfigReload {
 public:
  /// Loads and validates a config file (a service's load_*_config) and returns its log level;
  /// throws ConfigError when the file is invalid.
  using LoadLogLevel = std::function<std::string(const std::string& path)>;

  /// What one reload did.
  struct Outcome {
    /// Empty when the new file was valid; else the loader's message (nothing was applied).
    std::string error;
    /// The log level now in force.
    std::string log_level;
    /// The changed top-level keys left as they run (they need a restart).
    std::vector<std::string> needs_restart;
  };

  /// Remembers the file's YAML as the running configuration, whose log level is `log_level`.
  ConfigReload(std::string path, std::string log_level, LoadLogLevel load);

  /// Reads the file again and applies it as described above, logging what it did.
  Outcome reload();

 private:
  std::string path_;
  std::string log_level_;
  LoadLogLevel load_;
  YAML::Node running_;
};

}  // namespace litamin2::config

#include "litamin2/config/config_reload.hpp"

#include "litamin2/config/config_file.hpp"
#include "litamin2/service/logging.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <map>

namespace litamin2::config {
namespace {

constexpr const char* kLogLevelKey = "log_level";

std::map<std::string, std::string> emitted_keys(const YAML::Node& document) {
  std::map<std::string, std::string> keys;
  if (!document.IsMap()) return keys;
  for (const auto& entry : document) {
    YAML::Emitter out;
    out << entry.second;
    keys[entry.first.Scalar()] = out.c_str();
  }
  return keys;
}

}  // namespace

std::vector<std::string> changed_top_level_keys(const YAML::Node& before, const YAML::Node& after) {
  const auto a = emitted_keys(before);
  const auto b = emitted_keys(after);
  std::vector<std::string> changed;
  for (const auto& [key, text] : a) {
    const auto it = b.find(key);
    if (it == b.end() || it->second != text) changed.push_back(key);
  }
  for (const auto& [key, text] : b) {
    if (a.find(key) == a.end()) changed.push_back(key);
  }
  std::sort(changed.begin(), changed.end());
  return changed;
}

ConfigReload::ConfigReload(std::string path, std::string log_level, LoadLogLevel load)
    : path_(std::move(path)),
      log_level_(std::move(log_level)),
      load_(std::move(load)),
      running_(load_yaml_file(path_)) {}

ConfigReload::Outcome ConfigReload::reload() {
  Outcome outcome;
  std::string new_level;
  YAML::Node document;
  try {
    new_level = load_(path_);
    document = load_yaml_file(path_);
  } catch (const ConfigError& e) {
    outcome.error = e.what();
    outcome.log_level = log_level_;
    spdlog::error("reload: invalid configuration, nothing changed: {}", outcome.error);
    return outcome;
  }
  for (const std::string& key : changed_top_level_keys(running_, document)) {
    if (key == kLogLevelKey) continue;
    outcome.needs_restart.push_back(key);
    spdlog::warn("reload: '{}' changed in {}: it needs a restart, the running value stays", key,
                 path_);
  }
  if (new_level != log_level_) {
    service::set_log_level(new_level);
    spdlog::info("reload: log level {} -> {}", log_level_, new_level);
    log_level_ = new_level;
  }
  // The running configuration: what was, with the log level that was applied.
  if (document[kLogLevelKey]) {
    running_[kLogLevelKey] = document[kLogLevelKey];
  } else if (running_.IsMap()) {
    running_.remove(kLogLevelKey);
  }
  outcome.log_level = log_level_;
  if (outcome.needs_restart.empty() && outcome.error.empty())
    spdlog::info("reload: done, log level {}", log_level_);
  return outcome;
}

}  // namespace litamin2::config

#pragma once
/// Reading one YAML mapping of a config file: typed values, enums and ranges, unknown keys
/// rejected, and messages that name the key as a dotted path and quote the value.

#include "litamin2/core/config_error.hpp"

#include <yaml-cpp/yaml.h>

#include <set>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace litamin2::config {

/// The YAML text of a node, for error messages.
inline std::string yaml_text(const YAML::Node& node) {
  if (!node) return "";
  std::ostringstream out;
  out << node;
  std::string s = out.str();
  for (char& c : s)
    if (c == '\n') c = ' ';
  return s.size() > 80 ? s.substr(0, 77) + "..." : s;
}

/// Reads the keys of one YAML mapping, rejecting unknown keys; `path` is the dotted key path
/// used in messages.
class YamlSection {
 public:
  YamlSection(const YAML::Node& node, std::string path) : node_(node), path_(std::move(path)) {
    if (node_ && !node_.IsNull() && !node_.IsMap())
      throw ConfigError(name() + ": expected a mapping of keys to values, got '" +
                        yaml_text(node_) + "'");
  }

  template <class T>
  bool read(const std::string& key, T& field) {
    known_.insert(key);
    if (!node_ || !node_.IsMap() || !node_[key] || node_[key].IsNull()) return false;
    const YAML::Node value = node_[key];
    try {
      if (!value.IsScalar()) throw YAML::Exception(YAML::Mark(), "not a scalar");
      field = value.as<T>();
    } catch (const YAML::Exception&) {
      throw ConfigError(name(key) + ": cannot read '" + yaml_text(value) + "' as " +
                        type_name<T>());
    }
    return true;
  }

  /// Reads a number and checks lo <= value <= hi.
  template <class T>
  void read_range(const std::string& key, T& field, T lo, T hi) {
    if (!read(key, field)) return;
    if (!(field >= lo && field <= hi)) {
      std::ostringstream out;
      out << name(key) << ": " << yaml_text(node_[key]) << " is out of range [" << lo << ", " << hi
          << "]";
      throw ConfigError(out.str());
    }
  }

  /// Reads a string that must be one of `names`, and stores the matching value.
  template <class Enum>
  void read_enum(const std::string& key, Enum& field,
                 const std::vector<std::pair<std::string, Enum>>& names) {
    std::string text;
    if (!read(key, text)) return;
    for (const auto& [n, value] : names) {
      if (n == text) {
        field = value;
        return;
      }
    }
    std::string allowed;
    for (const auto& entry : names) allowed += (allowed.empty() ? "" : ", ") + entry.first;
    throw ConfigError(name(key) + ": '" + text + "' is not one of: " + allowed);
  }

  YAML::Node child(const std::string& key) {
    known_.insert(key);
    return node_ && node_.IsMap() ? node_[key] : YAML::Node();
  }

  void reject_unknown() const {
    if (!node_ || !node_.IsMap()) return;
    for (const auto& entry : node_) {
      const std::string key = entry.first.as<std::string>();
      if (!known_.count(key)) throw ConfigError(name(key) + ": unknown key");
    }
  }

  std::string name(const std::string& key = "") const {
    if (key.empty()) return path_.empty() ? std::string("config") : path_;
    return path_.empty() ? key : path_ + "." + key;
  }

 private:
  template <class T>
  static const char* type_name() {
    if constexpr (std::is_same_v<T, int>) return "an integer";
    if constexpr (std::is_same_v<T, double>) return "a number";
    if constexpr (std::is_same_v<T, bool>) return "true/false";
    return "a string";
  }

  YAML::Node node_;
  std::string path_;
  std::set<std::string> known_;
};

}  // namespace litamin2::config

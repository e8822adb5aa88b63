#pragma once
/// Reading one YAML mapping of a config file: typed values, enums and ranges, unknown keys
/// rejected, and messages that name the key as a dotted path and quote the value.

#include "litamin2/core/config_error.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <set>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace litamin2::config {

namespace detail {

/// Appends the flow-style text of `node` to `out` until it holds more than `budget` characters
/// (aliases can make a small document an exponentially large tree: never walk all of it).
inline void append_yaml_text(const YAML::Node& node, std::string& out, std::size_t budget) {
  if (out.size() > budget) return;
  switch (node.Type()) {
    case YAML::NodeType::Scalar:
      out += node.Scalar();
      return;
    case YAML::NodeType::Sequence: {
      out += '[';
      bool first = true;
      for (const auto& item : node) {
        if (out.size() > budget) break;
        out += first ? "" : ", ";
        first = false;
        append_yaml_text(item, out, budget);
      }
      out += ']';
      return;
    }
    case YAML::NodeType::Map: {
      out += '{';
      bool first = true;
      for (const auto& entry : node) {
        if (out.size() > budget) break;
        out += first ? "" : ", ";
        first = false;
        append_yaml_text(entry.first, out, budget);
        out += ": ";
        append_yaml_text(entry.second, out, budget);
      }
      out += '}';
      return;
    }
    default:
      return;
  }
}

}  // namespace detail

/// The YAML text of a node (flow style, at most 80 characters), for error messages.
inline std::string yaml_text(const YAML::Node& node) {
  if (!node) return "";
  std::string s;
  detail::append_yaml_text(node, s, 80);
  for (char& c : s)
    if (c == '\n') c = ' ';
  return s.size() > 80 ? s.substr(0, 77) + "..." : s;
}

/// The name of a mapping key; a key that is not a plain name (a sequence or a mapping used as a
/// key, `? {voxel_size: 3}`) is a ConfigError naming the mapping `path`.
inline std::string key_name(const YAML::Node& key, const std::string& path) {
  if (key.IsScalar()) return key.Scalar();
  throw ConfigError(path + ": a key must be a name, got '" + yaml_text(key) + "'");
}

/// Reads the keys of one YAML mapping, rejecting unknown keys; `path` is the dotted key path
/// used in messages. Every yaml-cpp exception becomes a ConfigError naming the key; numbers
/// must be finite (.inf and .nan are rejected wherever a number is read).
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
    if constexpr (std::is_floating_point_v<T>) {
      if (!std::isfinite(field))
        throw ConfigError(name(key) + ": '" + yaml_text(value) + "' is not a finite number");
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
      const std::string key = key_name(entry.first, name());
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
    if constexpr (std::is_floating_point_v<T>) return "a number";
    if constexpr (std::is_same_v<T, bool>) return "true/false";
    return "a string";
  }

  YAML::Node node_;
  std::string path_;
  std::set<std::string> known_;
};

}  // namespace litamin2::config

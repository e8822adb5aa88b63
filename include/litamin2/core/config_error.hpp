#pragma once

#include <stdexcept>

namespace litamin2 {

/// A configuration value that is missing, of the wrong type, out of range, or unknown. The
/// message names the key (as a dotted path) and the value.
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace litamin2

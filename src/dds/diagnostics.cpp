#include "litamin2/dds/diagnostics.hpp"

#include <cstdio>

namespace litamin2::dds {

diagnostic_msgs::msg::KeyValue key_value(const std::string& key, const std::string& value) {
  diagnostic_msgs::msg::KeyValue kv;
  kv.key(key);
  kv.value(value);
  return kv;
}

std::string fixed_number(double value, int decimals) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  return buffer;
}

}  // namespace litamin2::dds

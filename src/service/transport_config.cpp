#include "litamin2/service/transport_config.hpp"

#include <cstring>

namespace litamin2::service {

const char* to_string(DomainSource source) {
  switch (source) {
    case DomainSource::kDefault:
      return "default";
    case DomainSource::kConfig:
      return "config";
    case DomainSource::kEnvironment:
      return "ROS_DOMAIN_ID";
  }
  return "?";
}

std::optional<int> parse_ros_domain_id(const char* value, std::string* error) {
  if (value == nullptr || *value == '\0') return std::nullopt;
  const std::size_t length = std::strlen(value);
  bool digits = length <= 3;
  for (std::size_t i = 0; i < length && digits; ++i) digits = value[i] >= '0' && value[i] <= '9';
  int domain = -1;
  if (digits) {
    domain = 0;
    for (std::size_t i = 0; i < length; ++i) domain = 10 * domain + (value[i] - '0');
  }
  if (!digits || domain > 232) {
    if (error) {
      *error = std::string("ROS_DOMAIN_ID: '") + value +
               "' is not a DDS domain id (a whole number in 0..232)";
    }
    return std::nullopt;
  }
  return domain;
}

const char* to_string(TransportProfile profile) {
  switch (profile) {
    case TransportProfile::kLoopback:
      return "loopback";
    case TransportProfile::kShm:
      return "shm";
    case TransportProfile::kDefault:
      return "default";
    case TransportProfile::kXml:
      return "xml";
  }
  return "?";
}

}  // namespace litamin2::service

#include "litamin2/service/transport_config.hpp"

namespace litamin2::service {

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

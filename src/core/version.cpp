#include "litamin2/version.hpp"

namespace litamin2 {
const char* version() {
  return LITAMIN2_VERSION;
}
}  // namespace litamin2

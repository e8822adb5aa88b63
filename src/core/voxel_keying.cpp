#include "litamin2/core/voxel_keying.hpp"

#include <cstdlib>
#include <cstring>

namespace litamin2::sse2_voting {

bool cpu_has_avx2() {
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
  return __builtin_cpu_supports("avx2");
#else
  return false;
#endif
}

bool use_avx2_keying() {
  static const bool use = [] {
    const char* forced = std::getenv("LITAMIN2_KEYING");
    if (forced && std::strcmp(forced, "sse2") == 0) return false;
    return cpu_has_avx2();
  }();
  return use;
}

}  // namespace litamin2::sse2_voting

#include "litamin2/service/heap_tuning.hpp"

#include <malloc.h>

#include <climits>
#include <cstdlib>

namespace litamin2::service {

std::string keep_large_buffers_in_heap(std::size_t mmap_threshold_bytes) {
  for (const char* name : {"MALLOC_MMAP_THRESHOLD_", "MALLOC_TRIM_THRESHOLD_", "GLIBC_TUNABLES"}) {
    if (std::getenv(name) != nullptr)
      return std::string(name) + " is set: the allocator is kept as set";
  }
  if (mmap_threshold_bytes == 0 || mmap_threshold_bytes > static_cast<std::size_t>(INT_MAX) / 2)
    return "threshold out of range";
  const int threshold = static_cast<int>(mmap_threshold_bytes);
  if (mallopt(M_MMAP_THRESHOLD, threshold) != 1 || mallopt(M_TRIM_THRESHOLD, 2 * threshold) != 1)
    return "mallopt refused the thresholds";
  return {};
}

}  // namespace litamin2::service

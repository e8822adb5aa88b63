/// keep_large_buffers_in_heap: applied when the environment leaves the allocator alone, and
/// refused (with the reason) otherwise.

#include <gtest/gtest.h>

#include <cstdlib>

#include "litamin2/service/heap_tuning.hpp"

namespace litamin2::service {
namespace {

TEST(ServiceHeapTuning, AppliesTheThresholdsOrSaysWhyNot) {
  unsetenv("MALLOC_MMAP_THRESHOLD_");
  unsetenv("MALLOC_TRIM_THRESHOLD_");
  unsetenv("GLIBC_TUNABLES");
  EXPECT_EQ(keep_large_buffers_in_heap(), "");
  EXPECT_EQ(keep_large_buffers_in_heap(0), "threshold out of range");
}

TEST(ServiceHeapTuning, LeavesAnAllocatorSetThroughTheEnvironment) {
  setenv("MALLOC_MMAP_THRESHOLD_", "1048576", 1);
  EXPECT_EQ(keep_large_buffers_in_heap(),
            "MALLOC_MMAP_THRESHOLD_ is set: the allocator is kept as set");
  unsetenv("MALLOC_MMAP_THRESHOLD_");
}

}  // namespace
}  // namespace litamin2::service

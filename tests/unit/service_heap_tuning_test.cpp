/// keep_large_buffers_in_heap: applied when the environment leaves the allocator alone, and
/// refused (with the reason) otherwise. prefault_heap: what it touched is what later allocations
/// of any thread get, without page faults.

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <thread>
#include <vector>

#include "litamin2/service/heap_tuning.hpp"

namespace litamin2::service {
namespace {

void clear_allocator_environment() {
  for (const char* name :
       {"MALLOC_MMAP_THRESHOLD_", "MALLOC_TRIM_THRESHOLD_", "MALLOC_ARENA_MAX", "GLIBC_TUNABLES"})
    unsetenv(name);
}

long minor_faults() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_minflt;
}

/// Minor page faults while a new thread allocates `bytes` in 1 MiB blocks (heap-sized, below
/// the mmap threshold) and writes every byte, after `prefault_bytes` were touched (0: none),
/// measured in a child process: the allocator's state is the process's.
long faults_of_a_thread_allocating(std::size_t bytes, std::size_t prefault_bytes) {
  int result[2];
  if (pipe(result) != 0) return -1;
  const pid_t child = fork();
  if (child == 0) {
    long faults = -1;
    if (keep_large_buffers_in_heap().empty() &&
        prefault_heap(prefault_bytes).touched_bytes == prefault_bytes) {
      std::vector<char*> blocks;
      long before = 0;
      long after = 0;
      std::thread worker([&] {
        before = minor_faults();
        for (std::size_t done = 0; done < bytes; done += 1u << 20) {
          blocks.push_back(static_cast<char*>(std::malloc(1u << 20)));
          for (std::size_t i = 0; i < (1u << 20); ++i) blocks.back()[i] = static_cast<char>(i);
        }
        after = minor_faults();
      });
      worker.join();
      faults = after - before;
      for (char* block : blocks) std::free(block);
    }
    const ssize_t written = write(result[1], &faults, sizeof faults);
    _exit(written == sizeof faults ? 0 : 1);
  }
  close(result[1]);
  long faults = -1;
  if (read(result[0], &faults, sizeof faults) != sizeof faults) faults = -1;
  close(result[0]);
  int status = 0;
  waitpid(child, &status, 0);
  return faults;
}

TEST(ServiceHeapTuning, AppliesTheThresholdsOrSaysWhyNot) {
  clear_allocator_environment();
  EXPECT_EQ(keep_large_buffers_in_heap(), "");
  EXPECT_EQ(keep_large_buffers_in_heap(0), "threshold out of range");
}

TEST(ServiceHeapTuning, LeavesAnAllocatorSetThroughTheEnvironment) {
  setenv("MALLOC_MMAP_THRESHOLD_", "1048576", 1);
  EXPECT_EQ(keep_large_buffers_in_heap(),
            "MALLOC_MMAP_THRESHOLD_ is set: the allocator is kept as set");
  const HeapPrefault refused = prefault_heap(1u << 20);
  EXPECT_EQ(refused.touched_bytes, 0u);
  EXPECT_EQ(refused.refused, "MALLOC_MMAP_THRESHOLD_ is set: the allocator is kept as set");
  unsetenv("MALLOC_MMAP_THRESHOLD_");
  setenv("MALLOC_ARENA_MAX", "2", 1);
  EXPECT_EQ(prefault_heap(1u << 20).refused,
            "MALLOC_ARENA_MAX is set: the allocator is kept as set");
  unsetenv("MALLOC_ARENA_MAX");
}

TEST(ServiceHeapTuning, MoreThanHalfTheAvailableMemoryIsRefused) {
  clear_allocator_environment();
  const auto available = memory_available_bytes();
  ASSERT_TRUE(available.has_value());
  EXPECT_GT(*available, 0u);
  const HeapPrefault refused = prefault_heap(*available / 2 + (std::size_t{64} << 20));
  EXPECT_EQ(refused.touched_bytes, 0u);
  EXPECT_NE(refused.refused.find("MiB is more than half the memory available"), std::string::npos)
      << refused.refused;
}

TEST(ServiceHeapTuning, NothingToTouchOrNoChunkSize) {
  clear_allocator_environment();
  const HeapPrefault none = prefault_heap(0);
  EXPECT_EQ(none.touched_bytes, 0u);
  EXPECT_TRUE(none.refused.empty());
  EXPECT_EQ(prefault_heap(1u << 20, 0).refused, "chunk size 0");
}

TEST(ServiceHeapTuning, AnotherThreadAllocatesFromThePrefaultedPagesWithoutFaults) {
  clear_allocator_environment();
  constexpr std::size_t kAllocated = 32u << 20;  // 8192 pages of 4 KiB
  const long without = faults_of_a_thread_allocating(kAllocated, 0);
  const long with = faults_of_a_thread_allocating(kAllocated, 64u << 20);
  ASSERT_GE(without, 0);
  ASSERT_GE(with, 0);
  // Without: every page is faulted in (fewer with transparent huge pages, which would make
  // this check moot, so it is required to hold first).
  ASSERT_GT(without, 4000) << "the machine faults in fewer pages than written";
  EXPECT_LT(with, 200) << "faults with the heap touched before: " << with
                       << ", without: " << without;
}

}  // namespace
}  // namespace litamin2::service

#include "litamin2/service/heap_tuning.hpp"

#include <malloc.h>
#include <unistd.h>

#include <chrono>
#include <climits>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <vector>

namespace litamin2::service {
namespace {

/// The environment variable through which the operator set the allocator, if any.
std::optional<std::string> allocator_set_by_environment() {
  for (const char* name :
       {"MALLOC_MMAP_THRESHOLD_", "MALLOC_TRIM_THRESHOLD_", "MALLOC_ARENA_MAX", "GLIBC_TUNABLES"}) {
    if (std::getenv(name) != nullptr) return std::string(name);
  }
  return std::nullopt;
}

}  // namespace

std::optional<std::size_t> memory_available_bytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  std::size_t kib = 0;
  std::string unit;
  while (meminfo >> key >> kib >> unit) {
    if (key == "MemAvailable:") return kib * 1024;
  }
  return std::nullopt;
}

std::string keep_large_buffers_in_heap(std::size_t mmap_threshold_bytes) {
  if (const auto name = allocator_set_by_environment())
    return *name + " is set: the allocator is kept as set";
  if (mmap_threshold_bytes == 0 || mmap_threshold_bytes > static_cast<std::size_t>(INT_MAX) / 2)
    return "threshold out of range";
  const int threshold = static_cast<int>(mmap_threshold_bytes);
  if (mallopt(M_MMAP_THRESHOLD, threshold) != 1 || mallopt(M_TRIM_THRESHOLD, 2 * threshold) != 1)
    return "mallopt refused the thresholds";
  return {};
}

HeapPrefault prefault_heap(std::size_t bytes, std::size_t chunk_bytes) {
  HeapPrefault done;
  if (bytes == 0) return done;
  if (const auto name = allocator_set_by_environment()) {
    done.refused = *name + " is set: the allocator is kept as set";
    return done;
  }
  if (chunk_bytes == 0) {
    done.refused = "chunk size 0";
    return done;
  }
  // Touching more than the machine has would end in the OOM killer, not in an error.
  if (const auto available = memory_available_bytes(); available && bytes > *available / 2) {
    done.refused = std::to_string(bytes >> 20) + " MiB is more than half the memory available (" +
                   std::to_string(*available >> 20) + " MiB)";
    return done;
  }
  // -1 is glibc's "never" for the trim threshold (the value is read as unsigned).
  if (mallopt(M_ARENA_MAX, 1) != 1 || mallopt(M_TRIM_THRESHOLD, -1) != 1) {
    done.refused = "mallopt refused one arena without trimming";
    return done;
  }
  const auto start = std::chrono::steady_clock::now();
  const auto page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
  std::vector<void*> chunks;
  chunks.reserve(bytes / chunk_bytes + 1);
  for (std::size_t left = bytes; left > 0;) {
    const std::size_t size = left < chunk_bytes ? left : chunk_bytes;
    void* chunk = std::malloc(size);
    if (chunk == nullptr) {
      done.refused = "malloc failed after " + std::to_string(done.touched_bytes) + " bytes";
      break;
    }
    // Volatile: a store into memory that is freed unread may otherwise be left out.
    volatile char* bytes_of = static_cast<char*>(chunk);
    for (std::size_t i = 0; i < size; i += page) bytes_of[i] = 0;
    chunks.push_back(chunk);
    done.touched_bytes += size;
    left -= size;
  }
  for (auto it = chunks.rbegin(); it != chunks.rend(); ++it) std::free(*it);
  done.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return done;
}

}  // namespace litamin2::service

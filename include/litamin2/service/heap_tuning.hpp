#pragma once
/// The daemon's heap policy for scan-sized buffers, and its heap touched before the first scan.
///
/// Every received PointCloud2 (~1.5 MB for an HDL-64 scan) and every converted cloud is a fresh
/// allocation above glibc's mmap threshold, so by default each one is mmap'ed, page-faulted in
/// and munmap'ed again: measured with tests/integration/daemon_bench.sh PIN=1 (4 HDL-64-size
/// streams), about 1 ms of kernel CPU per frame, 40 % of the daemon's work outside tracking.
/// Keeping such buffers in the heap lets the next scan reuse the pages.
///
/// The pages are still touched for the first time while the first scans arrive: Fast DDS grows
/// each reader's payloads, the trackers' maps fill. Where a first touch is dear (15 us a 4 KiB
/// page on a VM measured in docs/benchmarks.md, "The heap touched before the first scan") that
/// is a backlog of seconds at start, and dropped frames. prefault_heap() moves it before the
/// first scan, as real-time programs lock and prefault their heap.

#include <cstddef>
#include <optional>
#include <string>

namespace litamin2::service {

/// Raises glibc malloc's mmap threshold to `mmap_threshold_bytes` (default 32 MiB: above the
/// largest scan of a 128-beam sensor) and its trim threshold to twice that, so that freed scan
/// buffers stay in the heap for reuse (the heap then keeps up to that much freed memory instead of
/// returning it at once). Does nothing and returns a reason when the operator set the allocator
/// through the environment (MALLOC_MMAP_THRESHOLD_, MALLOC_TRIM_THRESHOLD_, MALLOC_ARENA_MAX or
/// GLIBC_TUNABLES) or the call fails; empty on success.
std::string keep_large_buffers_in_heap(std::size_t mmap_threshold_bytes = 32u << 20);

/// What prefault_heap() did.
struct HeapPrefault {
  /// Bytes written, one byte a page, and then freed into the heap.
  std::size_t touched_bytes = 0;
  double seconds = 0.0;
  /// Non-empty: nothing was touched, and why.
  std::string refused;
};

/// Touches `bytes` of heap, in `chunk_bytes` allocations (below the mmap threshold, so that they
/// come from the heap), frees them and keeps them: one malloc arena for every thread created
/// afterwards (M_ARENA_MAX 1, so that the receive threads and the workers allocate from the
/// touched pages too) and no trimming (M_TRIM_THRESHOLD never: the process keeps its high-water
/// mark). Call it from the main thread before any other thread allocates. Refused when the
/// operator set the allocator through the environment (as keep_large_buffers_in_heap), when
/// `chunk_bytes` is 0, when `bytes` is more than half of memory_available_bytes(), or when an
/// allocation fails (what was touched is kept). 0 bytes: nothing.
HeapPrefault prefault_heap(std::size_t bytes, std::size_t chunk_bytes = 16u << 20);

/// MemAvailable of /proc/meminfo, in bytes; none when it cannot be read.
std::optional<std::size_t> memory_available_bytes();

}  // namespace litamin2::service

#pragma once
/// The daemon's heap policy for scan-sized buffers.
///
/// Every received PointCloud2 (~1.5 MB for an HDL-64 scan) and every converted cloud is a fresh
/// allocation above glibc's mmap threshold, so by default each one is mmap'ed, page-faulted in
/// and munmap'ed again: measured with tests/integration/daemon_bench.sh PIN=1 (4 HDL-64-size
/// streams), about 1 ms of kernel CPU per frame, 40 % of the daemon's work outside tracking.
/// Keeping such buffers in the heap lets the next scan reuse the pages.

#include <cstddef>
#include <string>

namespace litamin2::service {

/// Raises glibc malloc's mmap threshold to `mmap_threshold_bytes` (default 32 MiB: above the
/// largest scan of a 128-beam sensor) and its trim threshold to twice that, so that freed scan
/// buffers stay in the heap for reuse (the heap then keeps up to that much freed memory instead of
/// returning it at once). Does nothing and returns a reason when the operator set the allocator
/// through the environment (MALLOC_MMAP_THRESHOLD_, MALLOC_TRIM_THRESHOLD_ or GLIBC_TUNABLES) or
/// the call fails; empty on success.
std::string keep_large_buffers_in_heap(std::size_t mmap_threshold_bytes = 32u << 20);

}  // namespace litamin2::service

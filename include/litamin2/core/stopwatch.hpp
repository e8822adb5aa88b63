#pragma once
/// Wall-clock milliseconds since a time point: the stage timings of the tracker; the calling
/// thread's CPU time: the aggregator's per-stage accounting.

#include <chrono>
#include <ctime>

namespace litamin2 {

inline double elapsed_ms(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - since)
      .count();
}

/// CPU time consumed by the calling thread, seconds.
inline double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

}  // namespace litamin2

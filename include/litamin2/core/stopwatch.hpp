#pragma once
/// Wall-clock milliseconds since a time point: the stage timings of the tracker.

#include <chrono>

namespace litamin2 {

inline double elapsed_ms(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - since)
      .count();
}

}  // namespace litamin2

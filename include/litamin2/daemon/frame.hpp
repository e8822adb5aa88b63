#pragma once
/// One scan of a sensor stream as it travels from the DDS listener to its tracker.

#include "litamin2/core/point_cloud.hpp"
#include "litamin2/core/stamp.hpp"

#include <chrono>
#include <cstdint>

namespace litamin2::daemon {

struct Frame {
  /// The scan, sensor frame.
  PointCloud cloud;
  /// The input message's header stamp.
  Stamp stamp;
  /// When the listener received the sample (latency is measured from here).
  std::chrono::steady_clock::time_point arrival{};
  /// Per-stream arrival count, starting at 0 (dropped frames leave gaps).
  std::uint64_t sequence = 0;
};

}  // namespace litamin2::daemon

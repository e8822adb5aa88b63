#pragma once
/// One simulated sweep with the per-point data a driver publishes beside the coordinates.

#include <cstdint>
#include <vector>

#include "litamin2/core/point_cloud.hpp"

namespace litamin2::sim {

/// Points of one sweep, each in the sensor frame at its firing (raw, as drivers publish them),
/// with intensities, and for each point its firing time and ring.
struct SimulatedScan {
  /// Points and intensities in [0, 1].
  PointCloud cloud;
  /// Time of each point's firing from the sweep start, seconds (0 without sweep timing).
  std::vector<float> times;
  /// Ring of each point, 0 = the lowest beam (the Velodyne driver's convention).
  std::vector<std::uint16_t> rings;
};

}  // namespace litamin2::sim

#pragma once
/// How a LiDAR is installed on the vehicle and fired: the sweep's timing and motion, the
/// mount's tilt and the vehicle body it sees. With the defaults a scan is what the simulator
/// always cast: one pose, untilted, no self-hits.

#include "litamin2/sim/ego_body.hpp"
#include "litamin2/sim/sensor_mount.hpp"
#include "litamin2/sim/sweep.hpp"

namespace litamin2::sim {

/// Installation of a LidarModel on a vehicle.
struct SensorRig {
  /// Timing of a revolution and motion within it.
  SweepOptions sweep;
  /// Fixed tilt of the sensor on the vehicle.
  SensorMount mount;
  /// Parts of the vehicle that return points.
  EgoBody body;

  /// Validates the three parts (std::invalid_argument naming the bad value).
  void validate() const {
    sweep.validate();
    mount.validate();
    body.validate();
  }
};

}  // namespace litamin2::sim

#pragma once
/// Fleet planning: several vehicles driving the same streets of one simulated world (for
/// multi-stream load and map-merging tests).

#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace litamin2::sim {

/// Options of plan_fleet.
struct FleetOptions {
  /// Number of vehicles (>= 1).
  int vehicles = 2;
  /// Lateral offset of vehicles driving the route in reverse (the oncoming lane), metres,
  /// towards the left of the base trajectory.
  double lane_offset = 3.0;
};

/// One vehicle of a fleet.
struct FleetVehicle {
  /// Sensor (velodyne) poses in the world frame, one per frame at 10 Hz.
  std::vector<Eigen::Isometry3d> sensor_poses;
  /// Index into the base trajectory of each frame (before offsets).
  std::vector<std::size_t> source_frames;
  /// Human-readable description ("forward frames 0..99", "reverse, lane +3 m, ...").
  std::string description;
};

/// Plans `options.vehicles` runs of `count` frames on the base trajectory (world frame):
///  - vehicle 0 drives frames [first, first + count) as given;
///  - odd vehicles drive a window of the route in reverse (heading turned by 180 degrees,
///    shifted by lane_offset to the base trajectory's left), starting where the window ends;
///  - even vehicles >= 2 drive forward, time-shifted by k/2 * count/4 frames (backwards if the
///    trajectory ends too early), so they start elsewhere but share most of the streets;
///  - odd vehicles >= 3 use the same shifted windows as vehicle k-1, in reverse.
/// Throws std::invalid_argument if count is 0, the window exceeds the trajectory or
/// vehicles < 1.
std::vector<FleetVehicle> plan_fleet(const std::vector<Eigen::Isometry3d>& trajectory,
                                     std::size_t first, std::size_t count,
                                     const FleetOptions& options = {});

}  // namespace litamin2::sim

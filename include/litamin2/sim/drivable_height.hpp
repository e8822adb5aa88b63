#pragma once
/// A trajectory's heights made drivable. Some ground truths climb or fall where the vehicle
/// hardly moves (KITTI 08's first 100 frames rise 16 m over 40 m, 5.5 m of it at a near
/// standstill): no road can lie under every pose, and the World's road then cuts through the
/// scans (ground_clearance.hpp). limit_grade() bounds each step's height change by the grade
/// times its horizontal length plus a slack for ground-truth jitter, so the sensor's height
/// follows a road a vehicle could drive; orientations and horizontal positions are unchanged.

#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

namespace litamin2::sim {

/// Forward pass over `poses` (world frame, z up): pose i's height moves towards its own by at
/// most max_grade x (horizontal distance from pose i-1) + step_slack_m from pose i-1's
/// (repaired) height. Poses already within that bound keep their height exactly. Returns the
/// number of poses whose height changed.
std::size_t limit_grade(std::vector<Eigen::Isometry3d>& poses, double max_grade,
                        double step_slack_m);

}  // namespace litamin2::sim

#pragma once
/// Selecting the part of a trajectory around the simulated frames that the world must cover.

#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

namespace litamin2::sim {

/// The poses of frames [first, last) extended on both sides by up to `margin` metres of driven
/// distance (so geometry exists in sensor range before the first and after the last frame).
std::vector<Eigen::Isometry3d> trajectory_window(const std::vector<Eigen::Isometry3d>& trajectory,
                                                 std::size_t first, std::size_t last,
                                                 double margin = 150.0);

}  // namespace litamin2::sim

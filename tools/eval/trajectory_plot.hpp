#pragma once
/// Top-view plot of a ground-truth and an estimated trajectory, written as SVG or PNG.

#include <Eigen/Geometry>
#include <array>
#include <string>
#include <vector>

namespace litamin2::eval_tool {

/// The two position axes a top view shows: the two with the largest extent over both
/// trajectories, the lower-numbered one horizontal (to the right), the other vertical (upwards).
/// For KITTI camera-0 poses (x right, y down, z forward) this is x horizontal, z vertical; for
/// LiDAR / TUM-style poses with z up it is x horizontal, y vertical.
std::array<int, 2> top_view_axes(const std::vector<Eigen::Isometry3d>& gt,
                                 const std::vector<Eigen::Isometry3d>& est);

/// "svg" or "png" if a plot can be written to path (by its extension, case-insensitive; "png"
/// only when built with libpng), otherwise "".
std::string plot_format(const std::string& path);

/// Writes the top view of gt (black) and est (red) with equal scale on both axes. The format
/// follows the extension of path: ".svg" (plain polyline SVG) or ".png" (libpng). Throws
/// std::runtime_error naming the file for an unknown extension or a write failure.
void write_trajectory_plot(const std::string& path, const std::vector<Eigen::Isometry3d>& gt,
                           const std::vector<Eigen::Isometry3d>& est);

}  // namespace litamin2::eval_tool

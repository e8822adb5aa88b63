#pragma once
/// Plot of an estimated trajectory against the ground truth, drawn once with Cairo and written
/// as PNG, SVG or PDF: a top view with metre ticks, legend and a colour map of the position
/// error along the path, and the error over time below it.

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

/// "png", "svg" or "pdf" by the extension of path (case-insensitive), otherwise "".
std::string plot_format(const std::string& path);

/// A step of 1, 2 or 5 times a power of ten that divides `span` into at most `max_ticks`
/// intervals (and at least max_ticks / 5); 1 for a span that is not positive and finite.
double tick_step(double span, int max_ticks);

/// What a plot shows.
struct TrajectoryPlot {
  std::vector<Eigen::Isometry3d> ground_truth;
  /// The estimate as the ATE aligned it (alignment * pose, positions scaled for Sim(3)), pose i
  /// paired with ground-truth pose i.
  std::vector<Eigen::Isometry3d> aligned_estimate;
  /// Time of each pose in seconds (TUM), or empty: the error is then drawn over the pose index.
  std::vector<double> times;
  /// Title lines: e.g. the two file names, and the ATE.
  std::string title;
  std::string subtitle;
};

/// Writes the plot; the format follows the extension of path (see plot_format). Throws
/// std::runtime_error naming the file for an unknown extension, sizes that differ or a write
/// failure.
void write_trajectory_plot(const std::string& path, const TrajectoryPlot& plot);

}  // namespace litamin2::eval_tool

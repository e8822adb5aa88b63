#pragma once
/// A trajectory defined at every instant from poses at given times: SE(3) interpolation
/// between neighbouring samples (rotation by slerp, translation linearly), and constant
/// velocity (the first or last segment's) beyond the ends. The simulator casts each firing of
/// a sweep from it, so motion within the sweep follows the same path as the frame poses.

#include <Eigen/Geometry>
#include <vector>

namespace litamin2::sim {

/// Pose between a (s = 0) and b (s = 1): rotation by slerp, translation linearly; s outside
/// [0, 1] extrapolates with the same relative motion.
Eigen::Isometry3d interpolate_pose(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b,
                                   double s);

/// Poses at strictly increasing times, queried at any time.
class ContinuousTrajectory {
 public:
  /// Throws std::invalid_argument if the sizes differ, there are no poses, or the times are
  /// not strictly increasing and finite.
  ContinuousTrajectory(std::vector<Eigen::Isometry3d> poses, std::vector<double> times);
  /// Poses every `period` seconds from time 0.
  ContinuousTrajectory(std::vector<Eigen::Isometry3d> poses, double period);

  /// The pose at time t (interpolated; extrapolated at constant velocity outside the samples;
  /// a single sample is returned as it is).
  Eigen::Isometry3d pose_at(double t) const;
  /// Number of samples.
  std::size_t size() const { return poses_.size(); }
  /// Time of sample i.
  double time(std::size_t i) const { return times_[i]; }
  /// Sample i.
  const Eigen::Isometry3d& pose(std::size_t i) const { return poses_[i]; }

 private:
  std::vector<Eigen::Isometry3d> poses_;
  std::vector<double> times_;
};

}  // namespace litamin2::sim

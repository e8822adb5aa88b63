#pragma once
/// Registration of a raw scan to the map: voxelise the scan in the map's grid at the pose
/// estimate, run Newton (registration.hpp), and voxelise again at the new estimate while it
/// moved by more than the regrid tolerances (RegistrationConfig), at most max_regrids times and,
/// with regrid_contraction set, only while the corrections shrink.

#include "litamin2/core/registration.hpp"
#include "litamin2/core/voxelizer.hpp"

namespace litamin2 {

struct ScanRegistration {
  /// The last registration's result.
  RegistrationResult result;
  /// Distributions of the scan, sensor frame, cut in the grid of the final estimate's
  /// predecessor.
  std::vector<Distribution> source;
  /// The pose the scan's grid (source, and the voxeliser's last grid voxels) was cut at.
  Eigen::Isometry3d grid_pose = Eigen::Isometry3d::Identity();
  /// Number of times the scan was voxelised.
  int voxelizations = 0;
  /// The loop stopped because a re-voxelisation did not shrink the correction; `result` is then
  /// the previous pass's.
  bool regrid_stopped = false;
  /// Time spent voxelising, milliseconds.
  double voxelize_ms = 0.0;
  /// Time spent in Newton iterations, milliseconds.
  double register_ms = 0.0;

  /// Share of the scan's distributions that the result counted as inliers (0 if none).
  double inlier_share() const {
    return source.empty() ? 0.0 : static_cast<double>(result.inliers) / source.size();
  }
};

/// The re-grid loop's rule, apart from voxelising and registering: feed it each pass's result
/// and it says whether to voxelise again (at grid_pose()) and which result to keep.
class RegridLoop {
 public:
  RegridLoop(const RegistrationConfig& config, const Eigen::Isometry3d& initial);
  /// The pose the next pass cuts the scan's grid at.
  const Eigen::Isometry3d& grid_pose() const { return grid_pose_; }
  /// Takes the result of a pass registered from grid_pose(); true if another pass is to be made.
  bool next(const RegistrationResult& result);
  /// The result to keep: the last pass's, or the previous pass's when the loop stopped because a
  /// re-grid did not shrink the correction (its pose is then the last grid_pose()).
  const RegistrationResult& result() const { return result_; }
  /// The loop ended on a re-grid that did not shrink the correction.
  bool stopped() const { return stopped_; }
  /// Passes fed so far.
  int passes() const { return passes_; }

 private:
  const RegistrationConfig& config_;
  Eigen::Isometry3d grid_pose_;
  RegistrationResult result_;
  RegistrationResult previous_;
  double previous_correction_;
  int passes_ = 0;
  bool stopped_ = false;
};

ScanRegistration register_scan(const PointCloud& scan, Voxelizer& voxelizer, const VoxelMap& map,
                               const CorrespondenceSearch& search, const Eigen::Isometry3d& initial,
                               const RegistrationConfig& config);

}  // namespace litamin2

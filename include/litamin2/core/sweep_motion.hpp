#pragma once
/// The motion within a sweep estimated with the pose (continuous-time registration; added to
/// LiTAMIN2, whose KITTI scans come deskewed). Deskew (deskew.hpp) moves each point by the
/// sensor's motion from the scan's stamp to the point's time, at a twist taken from the motion
/// registered before: constant velocity. Where the velocity changes from one sweep to the next
/// (body roll and pitch, braking, a turn that starts), every point is moved a little wrong,
/// more the later it was fired, and the scan is bent.
///
/// Here the scan, deskewed with a twist xi0, is registered with a correction dxi of that twist
/// as well as its pose T: a distribution whose points were fired at mean time t (seconds after
/// the stamp) is placed at T Exp(t dxi) (to first order in dxi, the same as deskewing with
/// xi0 + dxi). A right perturbation e of dxi moves it by the left update t Ad_T e, so with the
/// ICP term's derivatives g_i, H_i for the left update of T (icp_term.hpp) the Newton system
/// over (left update of T, e) is
///
///   [ sum H_i            (sum t_i H_i) Ad_T        ] [ d ]     [ sum g_i                 ]
///   [ Ad_T^T (sum t_i H_i)  Ad_T^T (sum t_i^2 H_i) Ad_T + P ] [ e ] = - [ Ad_T^T sum t_i g_i + P
///   dxi ]
///
/// (registration.hpp's TimeWeightedSums), Ad_T = [[R, 0], [[p]x R, R]] for T = (R, p) in the
/// (phi, tau) order. P is a prior that keeps dxi near zero: the change of velocity from one
/// sweep to the next is small, and a scan alone constrains the twist weakly along some
/// directions (a straight corridor). In the cost's units P = 2 s^2 diag(1 / sigma_w^2,
/// 1 / sigma_v^2), s^2 the cost per residual degree of freedom (the scale the tracker's
/// covariance uses), so sigma_w, sigma_v read as the standard deviations of the twist's change.
/// The Cov term (Eq. 4) enters the pose block only.

#include "litamin2/core/correspondence_search.hpp"
#include "litamin2/core/deskew.hpp"
#include "litamin2/core/distribution.hpp"
#include "litamin2/core/point_cloud.hpp"
#include "litamin2/core/registration_config.hpp"
#include "litamin2/core/sweep_motion_config.hpp"
#include "litamin2/core/voxel_map.hpp"
#include "litamin2/core/voxelizer.hpp"

#include <Eigen/Geometry>
#include <vector>

namespace litamin2 {

/// Firing times of the points of each distribution `voxelizer.voxelize(scan, grid_pose)`
/// returned (its last call), in the same order: `times` has one time per point of `scan`.
/// Points are assigned to voxels as the voxeliser assigns them, in double precision (a point on
/// a voxel face may fall on the other side: its time is then missing from one mean).
struct DistributionTimes {
  /// Mean time of each distribution's points, seconds.
  std::vector<double> mean;
  /// Their standard deviation, seconds.
  std::vector<double> spread;
};
DistributionTimes distribution_times(const PointCloud& scan, const std::vector<float>& times,
                                     const Voxelizer& voxelizer);

struct SweepMotionResult {
  /// Pose of the scan at its stamp.
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  /// The correction dxi of the twist the scan was deskewed with (angular, linear; sensor frame).
  Twist correction;
  int iterations = 0;
  int correspondences = 0;
  /// False when too few correspondences or the system could not be solved; pose and
  /// correction are then the last valid ones (the initial ones at worst).
  bool valid = false;
};

/// Registers `source` (distributions of a scan deskewed with some twist, `times` their firing
/// times) to `map` from `initial`, with the twist's correction (see above). A distribution whose
/// times spread more than config.max_time_spread_s (one that holds both ends of the sweep, at
/// its cut, or a near one that spans a wide azimuth) is not moved by the correction: one time
/// does not describe it.
SweepMotionResult register_with_sweep_motion(const std::vector<Distribution>& source,
                                             const DistributionTimes& times, const VoxelMap& map,
                                             const CorrespondenceSearch& search,
                                             const Eigen::Isometry3d& initial,
                                             const RegistrationConfig& registration,
                                             const SweepMotionConfig& config);

}  // namespace litamin2

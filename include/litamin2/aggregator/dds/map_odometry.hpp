#pragma once
/// A vehicle's current pose in the shared map frame, from its odometry (rt/<stream>/odom) and
/// the mapper's latest estimate: the corrected pose of the stream's latest keyframe times the
/// inverse of that keyframe's odometry pose times the latest odometry pose,
///   T_map = K_corrected * K_odom^-1 * T_odom = C * T_odom,
/// with C = K_corrected * K_odom^-1 the stream's correction (Mapper::correction). Odometry
/// poses and keyframe odometry poses are in the same odometry frame (litamin2d publishes both),
/// so C is a change of that frame and the child frame (sensor or base) does not matter.

#include "geometry_msgs/msg/TransformStamped.h"
#include "litamin2/aggregator/aggregator_outputs.hpp"
#include "nav_msgs/msg/Odometry.h"

#include <Eigen/Geometry>
#include <optional>
#include <string>

namespace litamin2::aggregator {

/// How a stream's odometry poses go to the map frame.
struct MapCorrection {
  /// C = corrected pose of the stream's latest keyframe * inverse(its odometry pose).
  Eigen::Isometry3d correction = Eigen::Isometry3d::Identity();
  /// "map" when the stream's group is joined to the map's anchor stream, else
  /// "<anchor>/odom" (as in KeyframePoses).
  std::string frame_id;
};

/// C from a keyframe's corrected and odometry poses.
Eigen::Isometry3d odometry_correction(const Eigen::Isometry3d& corrected_keyframe,
                                      const Eigen::Isometry3d& keyframe_odom);
/// The correction a StreamPoses (the mapping thread's output for a stream) carries.
MapCorrection map_correction(const StreamPoses& poses);

/// `odom` moved to the map frame: header.frame_id = correction.frame_id, stamp and
/// child_frame_id kept, pose C * T_odom, pose covariance carried by the adjoint of C (the
/// odometry's covariance, not the map's uncertainty), twist unchanged (ROS expresses it in the
/// child frame).
nav_msgs::msg::Odometry to_map_odometry(const nav_msgs::msg::Odometry& odom,
                                        const MapCorrection& correction);

}  // namespace litamin2::aggregator

namespace litamin2::aggregator {

/// The correction as a tf2 transform for rt/tf: parent correction.frame_id ("map"), child the
/// odometry's frame (header.frame_id, "<stream>/odom"), the odometry's stamp, C itself. Sent
/// when C changes (MapOdometryRelay::set_correction) and with each map-frame pose (tf2 looks
/// transforms up by stamp and does not extrapolate from one sample, so a transform sent only
/// when C changes could not be looked up at later stamps). std::nullopt when both frames are the
/// same (the anchor stream before any merge: C is the identity and tf2 refuses a frame as its own
/// parent).
std::optional<geometry_msgs::msg::TransformStamped> to_map_transform(
    const nav_msgs::msg::Odometry& odom, const MapCorrection& correction);

}  // namespace litamin2::aggregator

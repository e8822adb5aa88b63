#include "litamin2/aggregator/dds/map_odometry.hpp"

#include "litamin2/aggregator/dds/aggregator_messages.hpp"
#include "litamin2/core/so3.hpp"
#include "litamin2/dds/odometry_conversion.hpp"
#include "litamin2/dds/pose_conversion.hpp"
#include "litamin2/dds/time_conversion.hpp"
#include "litamin2/dds/transform_conversion.hpp"

namespace litamin2::aggregator {

Eigen::Isometry3d odometry_correction(const Eigen::Isometry3d& corrected_keyframe,
                                      const Eigen::Isometry3d& keyframe_odom) {
  return corrected_keyframe * keyframe_odom.inverse();
}

MapCorrection map_correction(const StreamPoses& poses) {
  return {poses.correction, poses.in_map_frame ? std::string(kMapFrame) : poses.anchor + "/odom"};
}

nav_msgs::msg::Odometry to_map_odometry(const nav_msgs::msg::Odometry& odom,
                                        const MapCorrection& correction) {
  const dds::OdometrySample in = dds::from_odometry(odom).sample;
  const Eigen::Isometry3d& c = correction.correction;
  const Eigen::Isometry3d pose = c * in.pose;
  // C exp(xi) T = exp(Ad_C xi) C T: the left-update covariance moves by Ad_C, the same map as
  // a sensor extrinsic's.
  const Matrix6d left = transform_left_covariance(in.left_covariance, c);
  nav_msgs::msg::Odometry out = odom;
  out.header().frame_id(correction.frame_id);
  out.pose().pose(dds::to_pose_msg(pose));
  out.pose().covariance(dds::ros_pose_covariance(left, pose));
  return out;
}

std::optional<geometry_msgs::msg::TransformStamped> to_map_transform(
    const nav_msgs::msg::Odometry& odom, const MapCorrection& correction) {
  if (correction.frame_id == odom.header().frame_id()) return std::nullopt;
  return dds::to_transform_stamped(correction.correction, dds::to_stamp(odom.header().stamp()),
                                   correction.frame_id, odom.header().frame_id());
}

}  // namespace litamin2::aggregator

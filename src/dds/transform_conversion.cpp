#include "litamin2/dds/transform_conversion.hpp"

#include "litamin2/dds/pose_conversion.hpp"
#include "litamin2/dds/time_conversion.hpp"

namespace litamin2::dds {

geometry_msgs::msg::TransformStamped to_transform_stamped(const Eigen::Isometry3d& child_in_parent,
                                                          Stamp stamp,
                                                          const std::string& parent_frame,
                                                          const std::string& child_frame) {
  // The same numbers as the pose of the child in the parent (to_pose_msg), so an Odometry
  // message and the transform published with it agree bit for bit.
  const geometry_msgs::msg::Pose pose = to_pose_msg(child_in_parent);
  geometry_msgs::msg::TransformStamped msg;
  msg.header().stamp(to_time(stamp));
  msg.header().frame_id(parent_frame);
  msg.child_frame_id(child_frame);
  msg.transform().translation().x(pose.position().x());
  msg.transform().translation().y(pose.position().y());
  msg.transform().translation().z(pose.position().z());
  msg.transform().rotation(pose.orientation());
  return msg;
}

Eigen::Isometry3d from_transform_msg(const geometry_msgs::msg::Transform& msg) {
  geometry_msgs::msg::Pose pose;
  pose.position().x(msg.translation().x());
  pose.position().y(msg.translation().y());
  pose.position().z(msg.translation().z());
  pose.orientation(msg.rotation());
  return from_pose_msg(pose);
}

tf2_msgs::msg::TFMessage to_tf_message(geometry_msgs::msg::TransformStamped transform) {
  tf2_msgs::msg::TFMessage msg;
  msg.transforms().push_back(std::move(transform));
  return msg;
}

}  // namespace litamin2::dds

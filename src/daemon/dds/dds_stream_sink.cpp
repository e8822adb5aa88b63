#include "litamin2/daemon/dds/dds_stream_sink.hpp"

#include "litamin2/dds/odometry_conversion.hpp"
#include "litamin2/dds/pose_conversion.hpp"
#include "litamin2/msg/MapPatch.h"
#include "nav_msgs/msg/Odometry.h"

namespace litamin2::daemon {

namespace fdds = eprosima::fastdds::dds;

DdsStreamSink::DdsStreamSink(fdds::DataWriter* odom_writer, fdds::DataWriter* map_patch_writer,
                             std::string odom_frame, std::string base_frame)
    : odom_writer_(odom_writer),
      map_patch_writer_(map_patch_writer),
      odom_frame_(std::move(odom_frame)),
      base_frame_(std::move(base_frame)) {}

void DdsStreamSink::publish_odometry(const OdometryOutput& o) {
  nav_msgs::msg::Odometry msg =
      dds::to_odometry(o.pose, o.covariance, 0.0, odom_frame_, base_frame_);
  // The input's stamp, exactly (not through seconds as a double).
  msg.header().stamp().sec(o.stamp.sec);
  msg.header().stamp().nanosec(o.stamp.nanosec);
  if (!odom_writer_->write(&msg)) ++write_failures_;
}

void DdsStreamSink::publish_keyframe(const KeyframeOutput& k) {
  litamin2::msg::MapPatch msg;
  msg.stream_id(k.stream);
  msg.keyframe_id(k.keyframe_id);
  msg.stamp().sec(k.stamp.sec);
  msg.stamp().nanosec(k.stamp.nanosec);
  msg.frame_id(odom_frame_);
  msg.pose(dds::to_pose_msg(k.pose));
  msg.covariance(dds::ros_pose_covariance(k.covariance, k.pose));
  msg.voxel_size(static_cast<float>(k.voxel_size));
  auto& out = msg.distributions();
  out.resize(k.distributions.size());
  for (std::size_t i = 0; i < k.distributions.size(); ++i) {
    const Distribution& d = k.distributions[i];
    auto& v = out[i];
    v.mean({static_cast<float>(d.mean.x()), static_cast<float>(d.mean.y()),
            static_cast<float>(d.mean.z())});
    v.cov({static_cast<float>(d.cov(0, 0)), static_cast<float>(d.cov(0, 1)),
           static_cast<float>(d.cov(0, 2)), static_cast<float>(d.cov(1, 1)),
           static_cast<float>(d.cov(1, 2)), static_cast<float>(d.cov(2, 2))});
    v.count(static_cast<std::uint32_t>(d.count));
  }
  if (!map_patch_writer_->write(&msg)) ++write_failures_;
}

}  // namespace litamin2::daemon

#include "litamin2/daemon/dds/dds_stream_sink.hpp"

#include "litamin2/dds/map_patch_conversion.hpp"
#include "litamin2/dds/odometry_conversion.hpp"
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
      dds::to_odometry(o.pose, o.covariance, o.stamp, odom_frame_, base_frame_);
  if (!odom_writer_->write(&msg)) ++write_failures_;
}

void DdsStreamSink::publish_keyframe(const Keyframe& keyframe) {
  litamin2::msg::MapPatch msg = dds::to_map_patch(keyframe, odom_frame_);
  if (!map_patch_writer_->write(&msg)) ++write_failures_;
}

}  // namespace litamin2::daemon

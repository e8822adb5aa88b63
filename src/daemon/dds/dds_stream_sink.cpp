#include "litamin2/daemon/dds/dds_stream_sink.hpp"

#include "litamin2/dds/map_patch_conversion.hpp"
#include "litamin2/dds/odometry_conversion.hpp"
#include "litamin2/dds/transform_conversion.hpp"
#include "litamin2/msg/MapPatch.h"
#include "nav_msgs/msg/Odometry.h"
#include "tf2_msgs/msg/TFMessage.h"

namespace litamin2::daemon {

namespace fdds = eprosima::fastdds::dds;

DdsStreamSink::DdsStreamSink(fdds::DataWriter* odom_writer, fdds::DataWriter* map_patch_writer,
                             fdds::DataWriter* tf_writer, StreamFrames frames)
    : odom_writer_(odom_writer),
      map_patch_writer_(map_patch_writer),
      tf_writer_(tf_writer),
      frames_(std::move(frames)) {}

void DdsStreamSink::publish_odometry(const OdometryOutput& o) {
  nav_msgs::msg::Odometry msg =
      dds::to_odometry(o.pose, o.covariance, o.stamp, frames_.odom, frames_.base, o.twist);
  if (!odom_writer_->write(&msg)) ++write_failures_;
  if (tf_writer_ && !holding()) {
    tf2_msgs::msg::TFMessage tf =
        dds::to_tf_message(dds::to_transform_stamped(o.pose, o.stamp, frames_.odom, frames_.base));
    if (!tf_writer_->write(&tf)) ++write_failures_;
  }
}

void DdsStreamSink::publish_keyframe(const Keyframe& keyframe) {
  litamin2::msg::MapPatch msg = dds::to_map_patch(keyframe, frames_.odom);
  {
    std::lock_guard lock(hold_mutex_);
    if (holding_) {
      held_.push_back(std::move(msg));
      while (held_.size() > hold_capacity_) held_.pop_front();
      return;
    }
  }
  if (!map_patch_writer_->write(&msg)) ++write_failures_;
}

void DdsStreamSink::hold(std::size_t capacity) {
  std::lock_guard lock(hold_mutex_);
  holding_ = true;
  hold_capacity_ = capacity > 0 ? capacity : 1;
}

void DdsStreamSink::drop_held_before(std::uint64_t first_id) {
  std::lock_guard lock(hold_mutex_);
  while (!held_.empty() && held_.front().keyframe_id() < first_id) held_.pop_front();
}

std::size_t DdsStreamSink::release(std::uint64_t first_id) {
  std::lock_guard lock(hold_mutex_);
  std::size_t written = 0;
  for (litamin2::msg::MapPatch& msg : held_) {
    if (msg.keyframe_id() < first_id) continue;
    if (map_patch_writer_->write(&msg)) {
      ++written;
    } else {
      ++write_failures_;
    }
  }
  held_.clear();
  holding_ = false;
  return written;
}

bool DdsStreamSink::holding() const {
  std::lock_guard lock(hold_mutex_);
  return holding_;
}

}  // namespace litamin2::daemon

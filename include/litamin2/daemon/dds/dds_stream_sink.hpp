#pragma once
/// A stream's ResultSink on DDS: nav_msgs/Odometry on rt/<stream>/odom for every frame and a
/// litamin2 MapPatch on the shared map patches topic for every keyframe.

#include "litamin2/daemon/result_sink.hpp"

#include <fastdds/dds/publisher/DataWriter.hpp>

#include <string>

namespace litamin2::daemon {

class DdsStreamSink : public ResultSink {
 public:
  /// `odom_writer` (this stream's) and `map_patch_writer` (shared; DataWriter::write is
  /// thread-safe) must outlive the sink. Odometry headers name `odom_frame` and
  /// `base_frame`.
  DdsStreamSink(eprosima::fastdds::dds::DataWriter* odom_writer,
                eprosima::fastdds::dds::DataWriter* map_patch_writer, std::string odom_frame,
                std::string base_frame);

  void publish_odometry(const OdometryOutput& odometry) override;
  void publish_keyframe(const Keyframe& keyframe) override;

  /// Writes that DDS refused (e.g. a full history past its blocking time).
  std::uint64_t write_failures() const { return write_failures_; }

 private:
  eprosima::fastdds::dds::DataWriter* odom_writer_;
  eprosima::fastdds::dds::DataWriter* map_patch_writer_;
  std::string odom_frame_;
  std::string base_frame_;
  std::uint64_t write_failures_ = 0;
};

}  // namespace litamin2::daemon

#pragma once
/// A stream's ResultSink on DDS: nav_msgs/Odometry on rt/<stream>/odom for every frame (with
/// the twist since the previous frame when there is one), the same pose as odom -> base on
/// rt/tf (tf2_msgs/TFMessage) when a tf writer is given, and a litamin2 MapPatch on the map
/// patches topic (through the stream's writer, in the stream's partition) for every keyframe.

#include "litamin2/daemon/result_sink.hpp"
#include "litamin2/daemon/stream_frames.hpp"

#include <fastdds/dds/publisher/DataWriter.hpp>

#include <string>

namespace litamin2::daemon {

class DdsStreamSink : public ResultSink {
 public:
  /// `odom_writer` and `map_patch_writer` (this stream's), `tf_writer` (shared; DataWriter::write
  /// is thread-safe; `tf_writer` may be null: no rt/tf) must outlive the sink. Odometry headers
  /// and transforms name `frames.odom` and `frames.base`.
  DdsStreamSink(eprosima::fastdds::dds::DataWriter* odom_writer,
                eprosima::fastdds::dds::DataWriter* map_patch_writer,
                eprosima::fastdds::dds::DataWriter* tf_writer, StreamFrames frames);

  void publish_odometry(const OdometryOutput& odometry) override;
  void publish_keyframe(const Keyframe& keyframe) override;

  /// Writes that DDS refused (e.g. a full history past its blocking time).
  std::uint64_t write_failures() const { return write_failures_; }

 private:
  eprosima::fastdds::dds::DataWriter* odom_writer_;
  eprosima::fastdds::dds::DataWriter* map_patch_writer_;
  eprosima::fastdds::dds::DataWriter* tf_writer_;
  StreamFrames frames_;
  std::uint64_t write_failures_ = 0;
};

}  // namespace litamin2::daemon

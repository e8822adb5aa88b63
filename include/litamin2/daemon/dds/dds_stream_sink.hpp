#pragma once
/// A stream's ResultSink on DDS: nav_msgs/Odometry on rt/<stream>/odom for every frame (with
/// the twist since the previous frame when there is one), the same pose as odom -> base on
/// rt/tf (tf2_msgs/TFMessage) when a tf writer is given, and a litamin2 MapPatch on the map
/// patches topic (through the stream's writer, in the stream's partition) for every keyframe.

#include "litamin2/daemon/result_sink.hpp"
#include "litamin2/daemon/stream_frames.hpp"

#include "litamin2/msg/MapPatch.h"

#include <fastdds/dds/publisher/DataWriter.hpp>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <mutex>

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
  std::uint64_t write_failures() const { return write_failures_.load(); }

  /// Hot standby (ShardingConfig::replicas): from now on the map patches are held, the newest
  /// `capacity` of them, instead of written, and no rt/tf is written (that topic is shared by
  /// every stream: the owner's transforms only). Odometry is still written (exclusive
  /// ownership makes readers take the owner's).
  void hold(std::size_t capacity);
  /// Drops the held patches whose keyframe id is below `first_id` (the owner published them).
  void drop_held_before(std::uint64_t first_id);
  /// This daemon owns the stream again: writes the held patches whose keyframe id is at least
  /// `first_id` (those the old owner did not publish), oldest first, drops the rest and stops
  /// holding. Returns how many were written.
  std::size_t release(std::uint64_t first_id);
  bool holding() const;

 private:
  eprosima::fastdds::dds::DataWriter* odom_writer_;
  eprosima::fastdds::dds::DataWriter* map_patch_writer_;
  eprosima::fastdds::dds::DataWriter* tf_writer_;
  StreamFrames frames_;
  /// Written by the stream's worker and by release() on the main loop.
  std::atomic<std::uint64_t> write_failures_{0};
  mutable std::mutex hold_mutex_;
  bool holding_ = false;
  std::size_t hold_capacity_ = 0;
  std::deque<litamin2::msg::MapPatch> held_;
};

}  // namespace litamin2::daemon

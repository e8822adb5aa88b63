#pragma once
/// What a sharded daemon needs to take a stream over (stream_handover.hpp): for every stream it
/// knows of, the last odometry message on rt/<stream>/odom (whoever publishes it: this daemon
/// or the stream's current owner), the highest keyframe id seen on the map patches topic and
/// the stream's last map patches (at most MapSeedLimits::keyframes, kept as received and
/// converted only when a seed is asked for).
/// Readers are created by DaemonNode; this listener only records, under a lock, from Fast DDS's
/// threads. Messages are checked where they enter (dds::from_odometry); a rejected one is
/// counted, never recorded.

#include "litamin2/daemon/stream_handover.hpp"
#include "litamin2/msg/MapPatch.h"

#include <fastdds/dds/subscriber/DataReaderListener.hpp>

#include <cstdint>
#include <deque>
#include <map>
#include <mutex>
#include <optional>
#include <string>

namespace litamin2::daemon {

class HandoverListener : public eprosima::fastdds::dds::DataReaderListener {
 public:
  /// Readers of `odom_topic` (nav_msgs/Odometry) are for `stream`.
  void add_stream(const std::string& stream, const std::string& odom_topic);
  /// Readers of `topic` carry litamin2/msg/MapPatch.
  void set_map_patches_topic(const std::string& topic);
  /// How many of each stream's last patches are kept, and which of them seed (0: none).
  void set_map_seed_limits(const MapSeedLimits& limits);

  void on_data_available(eprosima::fastdds::dds::DataReader* reader) override;

  /// The seed for taking `stream` over: std::nullopt before any odometry of it was seen. Its
  /// map_keyframes are select_map_seed() of the kept patches that pass dds::from_map_patch
  /// (the others are counted in rejected()).
  std::optional<HandoverSeed> seed(const std::string& stream) const;
  /// The id after the highest keyframe id of `stream` seen on the map patches topic (0 when
  /// none was seen): where a promoted standby's held patches start (hot standby).
  std::uint64_t next_keyframe_id(const std::string& stream) const;
  /// Messages rejected by the checks.
  std::uint64_t rejected() const;

 private:
  void on_odometry(eprosima::fastdds::dds::DataReader* reader, const std::string& stream);
  void on_map_patches(eprosima::fastdds::dds::DataReader* reader);

  struct Known {
    std::optional<HandoverSeed> last;
    std::optional<std::uint64_t> last_keyframe_id;
    /// The last patches, oldest first, at most seed_limits_.keyframes.
    std::deque<litamin2::msg::MapPatch> patches;
  };
  MapSeedLimits seed_limits_;
  mutable std::mutex mutex_;
  std::map<std::string, std::string> odom_topics_;  // topic -> stream
  std::string map_patches_topic_;
  std::map<std::string, Known> streams_;
  mutable std::uint64_t rejected_ = 0;  // seed() counts the patches it rejects
};

}  // namespace litamin2::daemon

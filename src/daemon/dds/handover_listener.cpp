#include "litamin2/daemon/dds/handover_listener.hpp"

#include "litamin2/dds/map_patch_conversion.hpp"
#include "litamin2/dds/odometry_conversion.hpp"
#include "nav_msgs/msg/Odometry.h"

#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/topic/TopicDescription.hpp>

#include <algorithm>

namespace litamin2::daemon {

namespace fdds = eprosima::fastdds::dds;

void HandoverListener::add_stream(const std::string& stream, const std::string& odom_topic) {
  std::lock_guard lock(mutex_);
  odom_topics_[odom_topic] = stream;
  streams_.try_emplace(stream);
}

void HandoverListener::set_map_patches_topic(const std::string& topic) {
  std::lock_guard lock(mutex_);
  map_patches_topic_ = topic;
}

void HandoverListener::set_map_seed_limits(const MapSeedLimits& limits) {
  std::lock_guard lock(mutex_);
  seed_limits_ = limits;
}

void HandoverListener::on_data_available(fdds::DataReader* reader) {
  const std::string topic = reader->get_topicdescription()->get_name();
  std::string stream;
  bool patches = false;
  {
    std::lock_guard lock(mutex_);
    if (topic == map_patches_topic_) {
      patches = true;
    } else {
      const auto it = odom_topics_.find(topic);
      if (it == odom_topics_.end()) return;
      stream = it->second;
    }
  }
  if (patches)
    on_map_patches(reader);
  else
    on_odometry(reader, stream);
}

void HandoverListener::on_odometry(fdds::DataReader* reader, const std::string& stream) {
  nav_msgs::msg::Odometry msg;
  fdds::SampleInfo info;
  while (reader->take_next_sample(&msg, &info) == ReturnCode_t::RETCODE_OK) {
    if (!info.valid_data) continue;
    const dds::OdometryConversion c = dds::from_odometry(msg);
    std::lock_guard lock(mutex_);
    if (!c.ok()) {
      ++rejected_;
      continue;
    }
    HandoverSeed seed;
    seed.pose = c.sample.pose;
    seed.stamp = c.sample.stamp;
    // ROS's "unknown" twist has covariance -1 on the diagonal (dds::to_odometry without one).
    const auto& t = msg.twist();
    if (t.covariance()[0] >= 0.0) {
      Twist twist;
      twist.linear =
          Eigen::Vector3d(t.twist().linear().x(), t.twist().linear().y(), t.twist().linear().z());
      twist.angular = Eigen::Vector3d(t.twist().angular().x(), t.twist().angular().y(),
                                      t.twist().angular().z());
      seed.twist = twist;
    }
    Known& known = streams_[stream];
    // Keep the newest: after a handover both daemons may publish for a moment.
    if (!known.last || known.last->stamp < seed.stamp) {
      // The frame interval the twist spans: the gap to the previous message, if one frame's.
      if (known.last) {
        const double gap =
            static_cast<double>(seed.stamp.nanoseconds - known.last->stamp.nanoseconds) * 1e-9;
        seed.interval_s = gap <= 1.0 ? gap : 0.0;
      }
      known.last = seed;
    }
  }
}

void HandoverListener::on_map_patches(fdds::DataReader* reader) {
  litamin2::msg::MapPatch msg;
  fdds::SampleInfo info;
  while (reader->take_next_sample(&msg, &info) == ReturnCode_t::RETCODE_OK) {
    if (!info.valid_data) continue;
    std::lock_guard lock(mutex_);
    const auto it = streams_.find(msg.stream_id());
    if (it == streams_.end()) continue;  // a stream this daemon does not know (yet)
    it->second.last_keyframe_id =
        std::max(it->second.last_keyframe_id.value_or(0), msg.keyframe_id());
    if (seed_limits_.keyframes == 0) continue;
    it->second.patches.push_back(msg);
    while (it->second.patches.size() > seed_limits_.keyframes) it->second.patches.pop_front();
  }
}

std::uint64_t HandoverListener::next_keyframe_id(const std::string& stream) const {
  std::lock_guard lock(mutex_);
  const auto it = streams_.find(stream);
  if (it == streams_.end() || !it->second.last_keyframe_id) return 0;
  return *it->second.last_keyframe_id + 1;
}

std::optional<HandoverSeed> HandoverListener::seed(const std::string& stream) const {
  std::lock_guard lock(mutex_);
  const auto it = streams_.find(stream);
  if (it == streams_.end() || !it->second.last) return std::nullopt;
  HandoverSeed seed = *it->second.last;
  seed.next_keyframe_id = it->second.last_keyframe_id ? *it->second.last_keyframe_id + 1 : 0;
  std::vector<Keyframe> candidates;
  for (const litamin2::msg::MapPatch& patch : it->second.patches) {
    dds::PatchConversion c = dds::from_map_patch(patch);
    if (!c.ok()) {
      ++rejected_;
      continue;
    }
    candidates.push_back(std::move(c.keyframe));
  }
  seed.map_keyframes = select_map_seed(std::move(candidates), seed.stamp, seed_limits_);
  return seed;
}

std::uint64_t HandoverListener::rejected() const {
  std::lock_guard lock(mutex_);
  return rejected_;
}

}  // namespace litamin2::daemon

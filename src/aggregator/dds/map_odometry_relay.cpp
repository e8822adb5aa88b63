#include "litamin2/aggregator/dds/map_odometry_relay.hpp"

#include <vector>

namespace litamin2::aggregator {
namespace {

constexpr std::chrono::seconds kRateWindow(1);

}  // namespace

MapOdometryRelay::MapOdometryRelay() = default;

MapOdometryRelay::~MapOdometryRelay() {
  stop();
}

void MapOdometryRelay::add_stream(const std::string& stream, Publish publish,
                                  PublishTransform publish_transform) {
  std::lock_guard lock(mutex_);
  streams_[stream].publish = std::move(publish);
  streams_[stream].publish_transform = std::move(publish_transform);
}

void MapOdometryRelay::offer(const std::string& stream, nav_msgs::msg::Odometry odom,
                             Clock::time_point now) {
  {
    std::lock_guard lock(mutex_);
    Stream& s = streams_[stream];
    ++s.counts.received;
    s.last_seen = now;
    if (s.window_count == 0 && s.window_start == Clock::time_point{}) s.window_start = now;
    ++s.window_count;
    const std::chrono::duration<double> window = now - s.window_start;
    if (window >= kRateWindow) {
      // Messages after the window's first, over the time they span.
      s.counts.rate_hz = static_cast<double>(s.window_count - 1) / window.count();
      s.window_start = now;
      s.window_count = 1;
    }
    if (!s.correction) {
      ++s.counts.before_keyframe;
      return;
    }
    s.pending = std::move(odom);
    if (stopping_) return;
    pending_ = true;
  }
  wake_.notify_one();
}

void MapOdometryRelay::reject(const std::string& stream) {
  std::lock_guard lock(mutex_);
  ++streams_[stream].counts.rejected;
}

void MapOdometryRelay::set_correction(const std::string& stream, MapCorrection correction) {
  std::lock_guard lock(mutex_);
  Stream& s = streams_[stream];
  s.counts.frame_id = correction.frame_id;
  s.correction = std::move(correction);
}

void MapOdometryRelay::start() {
  std::lock_guard lock(mutex_);
  if (thread_.joinable() || stopping_) return;
  thread_ = std::thread([this] { run(); });
}

void MapOdometryRelay::stop() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_one();
  if (thread_.joinable()) thread_.join();
  flush();
}

void MapOdometryRelay::flush() {
  struct Work {
    const Publish* publish;
    const PublishTransform* publish_transform;
    nav_msgs::msg::Odometry odom;
    MapCorrection correction;
    Stream* stream;
  };
  std::vector<Work> work;
  {
    std::lock_guard lock(mutex_);
    pending_ = false;
    for (auto& [name, s] : streams_) {
      if (!s.pending) continue;
      if (s.publish)
        work.push_back(
            {&s.publish, &s.publish_transform, std::move(*s.pending), *s.correction, &s});
      s.pending.reset();
    }
  }
  // Streams are never removed and their publish function is set before their odometry is
  // read, so the pointers stay valid and unchanged outside the lock.
  for (Work& w : work) {
    (*w.publish)(to_map_odometry(w.odom, w.correction));
    if (*w.publish_transform) {
      if (const auto tf = to_map_transform(w.odom, w.correction)) (*w.publish_transform)(*tf);
    }
    std::lock_guard lock(mutex_);
    ++w.stream->counts.published;
  }
}

void MapOdometryRelay::run() {
  for (;;) {
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [this] { return pending_ || stopping_; });
      if (stopping_) return;
    }
    flush();
  }
}

std::map<std::string, OdometryStreamStatus> MapOdometryRelay::status(Clock::time_point now) const {
  std::lock_guard lock(mutex_);
  std::map<std::string, OdometryStreamStatus> out;
  for (const auto& [name, s] : streams_) {
    OdometryStreamStatus c = s.counts;
    if (s.counts.received > 0) {
      c.last_seen_s = std::chrono::duration<double>(now - s.last_seen).count();
      if (now - s.last_seen > kRateWindow) c.rate_hz = 0.0;
    }
    out.emplace(name, std::move(c));
  }
  return out;
}

}  // namespace litamin2::aggregator

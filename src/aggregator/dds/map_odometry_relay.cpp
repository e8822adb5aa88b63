#include "litamin2/aggregator/dds/map_odometry_relay.hpp"

#include <vector>

#include "litamin2/aggregator/dds/aggregator_messages.hpp"

namespace litamin2::aggregator {
namespace {

constexpr std::chrono::seconds kRateWindow(1);

}  // namespace

MapOdometryRelay::MapOdometryRelay(std::chrono::milliseconds map_frame_settle)
    : map_frame_settle_(map_frame_settle) {}

bool MapOdometryRelay::settling(Clock::time_point now) const {
  return !settle_end_ || now < *settle_end_;
}

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
    s.last_header = odom.header();
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
  {
    std::lock_guard lock(mutex_);
    if (!settle_end_) settle_end_ = Clock::now() + map_frame_settle_;
    Stream& s = streams_[stream];
    s.counts.frame_id = correction.frame_id;
    const bool changed = !s.correction || s.correction->frame_id != correction.frame_id ||
                         s.correction->correction.matrix() != correction.correction.matrix();
    s.correction = std::move(correction);
    // The transform goes out now, at the latest odometry's stamp, not only with the next pose
    // (which may never come: a stream that has stopped).
    if (!changed || !s.publish_transform || !s.last_header || stopping_) return;
    s.transform_pending = true;
    pending_ = true;
  }
  wake_.notify_one();
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
  std::vector<std::pair<const PublishTransform*, geometry_msgs::msg::TransformStamped>> transforms;
  {
    std::lock_guard lock(mutex_);
    pending_ = false;
    const bool hold_map_frame = settling(Clock::now());
    for (auto& [name, s] : streams_) {
      if (hold_map_frame && s.correction && s.correction->frame_id == kMapFrame &&
          (s.pending || s.transform_pending)) {
        held_ = true;  // run() flushes again when the settling ends
        continue;
      }
      if (s.transform_pending && !s.pending && s.last_header->stamp() != s.transform_stamp) {
        // A changed correction without a new pose to carry it, at the latest odometry's stamp
        // unless a transform went out at that stamp already: tf2 ignores a repeated stamp
        // (TF_REPEATED_DATA), the next pose then carries the correction.
        nav_msgs::msg::Odometry latest;
        latest.header(*s.last_header);
        if (const auto tf = to_map_transform(latest, *s.correction)) {
          transforms.emplace_back(&s.publish_transform, *tf);
          s.transform_stamp = tf->header().stamp();
        }
      }
      s.transform_pending = false;
      if (!s.pending) continue;
      if (s.publish_transform) s.transform_stamp = s.pending->header().stamp();
      if (s.publish)
        work.push_back(
            {&s.publish, &s.publish_transform, std::move(*s.pending), *s.correction, &s});
      s.pending.reset();
    }
  }
  // Streams are never removed and their publish function is set before their odometry is
  // read, so the pointers stay valid and unchanged outside the lock.
  for (const auto& [publish_transform, tf] : transforms) (*publish_transform)(tf);
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
      const auto ready = [this] { return pending_ || stopping_; };
      if (held_ && settle_end_) {
        wake_.wait_until(lock, *settle_end_, ready);
        held_ = false;
      } else {
        wake_.wait(lock, ready);
      }
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

#include "litamin2/daemon/stream_stats.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace litamin2::daemon {

double quantile(std::vector<double>& values, double q) {
  if (values.empty()) return 0.0;
  q = std::clamp(q, 0.0, 1.0);
  // Nearest rank: the smallest value with at least q of the values at or below it.
  std::size_t rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(values.size())));
  rank = std::clamp<std::size_t>(rank, 1, values.size());
  std::nth_element(values.begin(), values.begin() + (rank - 1), values.end());
  return values[rank - 1];
}

StreamStats::StreamStats(std::chrono::duration<double> window, std::size_t max_samples)
    : window_(std::chrono::duration_cast<Clock::duration>(window)),
      max_samples_(std::max<std::size_t>(max_samples, 1)) {}

void StreamStats::record_received() {
  std::lock_guard lock(mutex_);
  ++counters_.frames_received;
}

void StreamStats::record_bad_message(const std::string& reason) {
  record_bad_messages(reason, 1);
}

void StreamStats::record_bad_messages(const std::string& reason, std::uint64_t count) {
  if (count == 0) return;
  std::lock_guard lock(mutex_);
  counters_.bad_messages += count;
  counters_.bad_message_reasons[reason] += count;
}

void StreamStats::record_out_of_order() {
  std::lock_guard lock(mutex_);
  ++counters_.frames_out_of_order;
}

void StreamStats::record_non_finite_points(std::uint64_t points) {
  std::lock_guard lock(mutex_);
  counters_.points_non_finite += points;
}

void StreamStats::record_dropped(std::uint64_t frames) {
  std::lock_guard lock(mutex_);
  counters_.frames_dropped += frames;
}

void StreamStats::record_failed() {
  std::lock_guard lock(mutex_);
  ++counters_.frames_failed;
}

void StreamStats::record_tracking_cpu(double seconds) {
  std::lock_guard lock(mutex_);
  counters_.tracking_cpu_s += seconds;
}

void StreamStats::record_result(Clock::time_point arrival, Clock::time_point published,
                                bool keyframe, bool registered, std::size_t map_size) {
  const double latency_ms = std::chrono::duration<double, std::milli>(published - arrival).count();
  std::lock_guard lock(mutex_);
  ++counters_.frames_processed;
  if (keyframe) ++counters_.keyframes;
  if (!registered) ++counters_.frames_unregistered;
  counters_.map_size = map_size;
  counters_.latency_seconds.observe(latency_ms * 1e-3);
  samples_.push_back({published, latency_ms});
  while (samples_.size() > max_samples_) samples_.pop_front();
}

void StreamStats::expire(Clock::time_point now) const {
  while (!samples_.empty() && samples_.front().published < now - window_) samples_.pop_front();
}

StatsSnapshot StreamStats::snapshot(Clock::time_point now) const {
  std::lock_guard lock(mutex_);
  expire(now);
  StatsSnapshot s = counters_;
  s.window_samples = samples_.size();
  if (samples_.empty()) return s;
  std::vector<double> latencies;
  latencies.reserve(samples_.size());
  for (const Sample& sample : samples_) latencies.push_back(sample.latency_ms);
  s.latency_max_ms = *std::max_element(latencies.begin(), latencies.end());
  s.latency_p50_ms = quantile(latencies, 0.5);
  s.latency_p99_ms = quantile(latencies, 0.99);
  if (samples_.size() >= 2) {
    const double span =
        std::chrono::duration<double>(samples_.back().published - samples_.front().published)
            .count();
    if (span > 0) s.frames_per_second = static_cast<double>(samples_.size() - 1) / span;
  }
  return s;
}

}  // namespace litamin2::daemon

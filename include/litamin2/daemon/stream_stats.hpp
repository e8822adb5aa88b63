#pragma once
/// Per-stream counters and the latency from sample arrival to result published, with p50/p99
/// and frames/s over a sliding time window. Thread-safe: the listener, the stream's task and
/// the status publisher update and read it concurrently.

#include "litamin2/service/histogram.hpp"

#include <chrono>
#include <cstdint>
#include <deque>
#include <map>
#include <mutex>
#include <string>
#include <vector>

namespace litamin2::daemon {

/// A consistent copy of a stream's statistics.
struct StatsSnapshot {
  /// Frames received and converted (bad messages are not frames).
  std::uint64_t frames_received = 0;
  /// Frames whose result was published.
  std::uint64_t frames_processed = 0;
  /// Frames dropped because the stream fell behind (or at shutdown).
  std::uint64_t frames_dropped = 0;
  /// Messages rejected by validation, and scans with no finite point (empty, or all NaN/Inf).
  std::uint64_t bad_messages = 0;
  /// bad_messages by reason (the conversion's error code, "malformed_cdr", "empty").
  std::map<std::string, std::uint64_t> bad_message_reasons;
  /// Valid scans dropped because their header stamp was not later than the last accepted
  /// scan's of the stream (a stamp going backwards, or a duplicate): never processed.
  std::uint64_t frames_out_of_order = 0;
  /// Points with a NaN/Inf coordinate dropped from received scans (the rest of the scan is
  /// processed).
  std::uint64_t points_non_finite = 0;
  /// Frames whose processing failed (exception).
  std::uint64_t frames_failed = 0;
  /// Frames whose registration did not converge (pose from the motion prediction).
  std::uint64_t frames_unregistered = 0;
  std::uint64_t keyframes = 0;
  /// Distributions in the stream's map after the last frame.
  std::size_t map_size = 0;
  /// Results per second over the window (0 with fewer than two results in it).
  double frames_per_second = 0.0;
  /// Arrival -> published latency over the window, milliseconds (0 when the window is empty).
  double latency_p50_ms = 0.0;
  double latency_p99_ms = 0.0;
  double latency_max_ms = 0.0;
  /// Results in the window.
  std::size_t window_samples = 0;
  /// CPU time the stream's tracker spent in Tracker::process over every processed frame (its
  /// thread's CPU clock), seconds: with the process's CPU time it separates tracking from the
  /// rest of the daemon's work per frame (transport, conversion, publishing).
  double tracking_cpu_s = 0.0;
  /// Arrival -> published latency of every processed frame since the start, seconds (for the
  /// Prometheus histogram; the window's quantiles above are for the status).
  service::Histogram latency_seconds{service::latency_buckets_seconds()};
};

class StreamStats {
 public:
  using Clock = std::chrono::steady_clock;

  /// Keeps results of the last `window` (and at most `max_samples` of them).
  explicit StreamStats(std::chrono::duration<double> window = std::chrono::seconds(10),
                       std::size_t max_samples = 4096);

  void record_received();
  /// A rejected message; `reason` is its short code (dds::to_string of the error).
  void record_bad_message(const std::string& reason);
  /// `count` rejected messages of one reason (nothing for 0).
  void record_bad_messages(const std::string& reason, std::uint64_t count);
  void record_out_of_order();
  void record_non_finite_points(std::uint64_t points);
  void record_dropped(std::uint64_t frames = 1);
  void record_failed();
  /// CPU seconds one frame's tracking took (added to tracking_cpu_s).
  void record_tracking_cpu(double seconds);
  /// A result published at `published` for a frame that arrived at `arrival`.
  void record_result(Clock::time_point arrival, Clock::time_point published, bool keyframe,
                     bool registered, std::size_t map_size);

  /// Statistics with the window ending at `now`.
  StatsSnapshot snapshot(Clock::time_point now = Clock::now()) const;

 private:
  struct Sample {
    Clock::time_point published;
    double latency_ms;
  };
  void expire(Clock::time_point now) const;

  const Clock::duration window_;
  const std::size_t max_samples_;
  mutable std::mutex mutex_;
  mutable std::deque<Sample> samples_;
  StatsSnapshot counters_;
};

/// The q-quantile (0..1) of `values` by the nearest-rank method; 0 for no values. Reorders
/// `values`.
double quantile(std::vector<double>& values, double q);

}  // namespace litamin2::daemon

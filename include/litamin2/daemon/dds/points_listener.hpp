#pragma once
/// The reader listener of one stream's rt/<stream>/points (or of one sensor's topic of a stream
/// of several, MergedInput): takes each PointCloud2 sample, validates and converts it
/// (litamin2::dds::from_pointcloud2), and hands it on (the stream's scheduler queue, or the
/// merge); a bad message is counted and logged (rate-limited), never processed. It never
/// blocks on processing: the scheduler's queue drops the oldest frame when the stream is behind.
///
/// Besides the message checks of the conversion:
///  - points with a NaN/Inf coordinate are dropped and counted (points_non_finite); a scan
///    left with no point (width * height == 0, or every point non-finite) is a bad message:
///    the tracker can do nothing with it but extrapolate;
///  - header stamps must increase strictly within a stream: a scan stamped at or before the
///    last accepted one (reordered, duplicated or replayed) is dropped and counted
///    (frames_out_of_order), so that the tracker's constant-velocity prediction and the
///    odometry's stamps only move forward. A newly matched publisher may restart its stamps:
///    the check then starts over (the tracker is not reset).

#include "litamin2/daemon/stream_scheduler.hpp"
#include "litamin2/daemon/stream_stats.hpp"
#include "litamin2/dds/pointcloud2_conversion.hpp"
#include "litamin2/service/log_rate_limiter.hpp"

#include <fastdds/dds/subscriber/DataReaderListener.hpp>

#include <functional>
#include <mutex>
#include <optional>
#include <string>

namespace litamin2::daemon {

class PointsListener : public eprosima::fastdds::dds::DataReaderListener {
 public:
  /// Takes each accepted scan (called on the DDS listener thread).
  using Deliver = std::function<void(Frame)>;
  /// Called when a new publisher matched (its stamps may start over).
  using NewPublisher = std::function<void()>;

  /// Queues the scans on `scheduler`; `scheduler` and `stats` must outlive the listener.
  PointsListener(std::string stream, StreamScheduler& scheduler, StreamScheduler::Handle handle,
                 StreamStats& stats, dds::CloudConversionOptions options = {});
  /// Hands the scans to `deliver`; `stats` must outlive the listener. `name` names the input in
  /// logs (the stream id, or "<stream> input <topic>").
  PointsListener(std::string name, Deliver deliver, NewPublisher new_publisher, StreamStats& stats,
                 dds::CloudConversionOptions options);

  void on_data_available(eprosima::fastdds::dds::DataReader* reader) override;
  void on_subscription_matched(
      eprosima::fastdds::dds::DataReader* reader,
      const eprosima::fastdds::dds::SubscriptionMatchedStatus& info) override;
  void on_sample_lost(eprosima::fastdds::dds::DataReader* reader,
                      const eprosima::fastdds::dds::SampleLostStatus& status) override;

  /// Samples DDS reported lost (best-effort fragments that did not arrive).
  std::uint64_t samples_lost() const { return samples_lost_.load(); }

  /// The checks after conversion (a bad or empty scan, the stamp order) and the hand-over, for
  /// a scan converted by this listener or by another reader of the same stream (the zero-copy
  /// input, PlainScanListener). Moves the cloud out of `conversion` when the scan is accepted.
  /// `kind` names the message type in logs.
  void accept(dds::CloudConversion& conversion, const builtin_interfaces::msg::Time& stamp_msg,
              std::chrono::steady_clock::time_point arrival, const char* kind = "PointCloud2");
  /// Counts a bad message of another reader of the stream (`reason` is its counter's label)
  /// and logs it, rate-limited, as this listener logs its own.
  void reject(const char* kind, const char* reason, const std::string& detail);

 private:
  void log_bad(const char* kind, const char* what, const std::string& detail);

  const std::string stream_;
  const Deliver deliver_;
  const NewPublisher new_publisher_;
  StreamStats& stats_;
  const dds::CloudConversionOptions options_;
  service::LogRateLimiter bad_message_log_;
  service::LogRateLimiter out_of_order_log_;
  /// The stamp of the last accepted scan (none before the first, or after a new publisher).
  std::mutex stamp_mutex_;
  std::optional<Stamp> last_stamp_;
  std::atomic<std::uint64_t> sequence_{0};
  std::atomic<std::uint64_t> samples_lost_{0};
};

}  // namespace litamin2::daemon

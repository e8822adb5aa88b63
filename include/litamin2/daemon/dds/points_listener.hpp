#pragma once
/// The reader listener of one stream's rt/<stream>/points: takes each PointCloud2 sample,
/// validates and converts it (litamin2::dds::from_pointcloud2), and queues it on the stream's
/// scheduler; a bad message is counted and logged (rate-limited), never processed. It never
/// blocks on processing: the scheduler's queue drops the oldest frame when the stream is behind.

#include "litamin2/daemon/log_rate_limiter.hpp"
#include "litamin2/daemon/stream_scheduler.hpp"
#include "litamin2/daemon/stream_stats.hpp"
#include "litamin2/dds/pointcloud2_conversion.hpp"

#include <fastdds/dds/subscriber/DataReaderListener.hpp>

#include <string>

namespace litamin2::daemon {

class PointsListener : public eprosima::fastdds::dds::DataReaderListener {
 public:
  /// `scheduler` and `stats` must outlive the listener.
  PointsListener(std::string stream, StreamScheduler& scheduler, StreamScheduler::Handle handle,
                 StreamStats& stats, dds::CloudConversionOptions options = {});

  void on_data_available(eprosima::fastdds::dds::DataReader* reader) override;
  void on_subscription_matched(
      eprosima::fastdds::dds::DataReader* reader,
      const eprosima::fastdds::dds::SubscriptionMatchedStatus& info) override;
  void on_sample_lost(eprosima::fastdds::dds::DataReader* reader,
                      const eprosima::fastdds::dds::SampleLostStatus& status) override;

  /// Samples DDS reported lost (best-effort fragments that did not arrive).
  std::uint64_t samples_lost() const { return samples_lost_.load(); }

 private:
  const std::string stream_;
  StreamScheduler& scheduler_;
  const StreamScheduler::Handle handle_;
  StreamStats& stats_;
  const dds::CloudConversionOptions options_;
  LogRateLimiter bad_message_log_;
  std::atomic<std::uint64_t> sequence_{0};
  std::atomic<std::uint64_t> samples_lost_{0};
};

}  // namespace litamin2::daemon

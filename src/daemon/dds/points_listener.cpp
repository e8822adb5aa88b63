#include "litamin2/daemon/dds/points_listener.hpp"

#include "litamin2/dds/checked_type.hpp"
#include "litamin2/dds/pointcloud2_scan_type.hpp"
#include "litamin2/dds/time_conversion.hpp"

#include <spdlog/spdlog.h>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>

namespace litamin2::daemon {

namespace fdds = eprosima::fastdds::dds;

PointsListener::PointsListener(std::string stream, StreamScheduler& scheduler,
                               StreamScheduler::Handle handle, StreamStats& stats,
                               dds::CloudConversionOptions options)
    : PointsListener(
          std::move(stream),
          [&scheduler, handle](Frame frame) { scheduler.submit(handle, std::move(frame)); }, {},
          stats, options) {}

PointsListener::PointsListener(std::string name, Deliver deliver, NewPublisher new_publisher,
                               StreamStats& stats, dds::CloudConversionOptions options)
    : stream_(std::move(name)),
      deliver_(std::move(deliver)),
      new_publisher_(std::move(new_publisher)),
      stats_(stats),
      options_(options) {}

void PointsListener::log_bad(const char* kind, const char* what, const std::string& detail) {
  if (const auto suppressed = bad_message_log_.allow())
    spdlog::warn("stream {}: dropped a bad {} ({}: {}){}", stream_, kind, what, detail,
                 *suppressed ? fmt::format(" and {} more since the last report", *suppressed)
                             : std::string());
}

void PointsListener::on_data_available(fdds::DataReader* reader) {
  // The reader's type is a dds::PointCloud2ScanType: take_next_sample deserialises the
  // message's members and converts its points straight from Fast DDS's copy of the payload.
  dds::ReceivedPointCloud2 scan;
  scan.options = options_;
  fdds::SampleInfo info;
  // Fast DDS drops (inside take_next_sample) a sample the type could not deserialise; count
  // those.
  dds::take_sample_failures();
  const auto count_failures = [&] {
    const dds::SampleFailures failed = dds::take_sample_failures();
    if (failed.count() == 0) return;
    stats_.record_bad_messages(dds::to_string(dds::SampleError::kMalformed), failed.malformed);
    stats_.record_bad_messages(dds::to_string(dds::SampleError::kTooLarge), failed.too_large);
    log_bad("PointCloud2", dds::to_string(failed.last_error), failed.last_message);
  };
  for (;;) {
    const bool taken = reader->take_next_sample(&scan, &info) == ReturnCode_t::RETCODE_OK;
    count_failures();
    if (!taken) break;
    if (!info.valid_data) continue;
    accept(scan.conversion, scan.meta.header().stamp(), std::chrono::steady_clock::now());
  }
}

void PointsListener::reject(const char* kind, const char* reason, const std::string& detail) {
  stats_.record_bad_message(reason);
  log_bad(kind, reason, detail);
}

void PointsListener::accept(dds::CloudConversion& conversion,
                            const builtin_interfaces::msg::Time& stamp_msg,
                            std::chrono::steady_clock::time_point arrival, const char* kind) {
  if (conversion.error != dds::CloudError::kNone) {
    stats_.record_bad_message(dds::to_string(conversion.error));
    log_bad(kind, dds::to_string(conversion.error), conversion.message);
    return;
  }
  if (conversion.non_finite > 0) stats_.record_non_finite_points(conversion.non_finite);
  if (conversion.cloud.points.empty()) {
    stats_.record_bad_message("empty");
    log_bad(kind, "empty",
            fmt::format("no finite point among {} point(s)", conversion.total_points));
    return;
  }
  const Stamp stamp = dds::to_stamp(stamp_msg);
  std::optional<Stamp> previous;
  {
    std::lock_guard lock(stamp_mutex_);
    if (last_stamp_ && !(*last_stamp_ < stamp)) {
      previous = last_stamp_;
    } else {
      last_stamp_ = stamp;
    }
  }
  if (previous) {
    stats_.record_out_of_order();
    if (const auto suppressed = out_of_order_log_.allow())
      spdlog::warn(
          "stream {}: dropped a scan stamped {}.{:09d}, not after the last one ({}.{:09d}){}",
          stream_, stamp_msg.sec(), stamp_msg.nanosec(), dds::to_time(*previous).sec(),
          dds::to_time(*previous).nanosec(),
          *suppressed ? fmt::format(" and {} more since the last report", *suppressed)
                      : std::string());
    return;
  }
  Frame frame;
  frame.cloud = std::move(conversion.cloud);
  conversion.cloud = PointCloud();
  frame.stamp = stamp;
  frame.arrival = arrival;
  frame.sequence = sequence_.fetch_add(1);
  stats_.record_received();
  deliver_(std::move(frame));
}

void PointsListener::on_subscription_matched(fdds::DataReader*,
                                             const fdds::SubscriptionMatchedStatus& info) {
  spdlog::info("stream {}: {} publisher(s) matched", stream_, info.current_count);
  if (info.current_count_change > 0) {
    // A new publisher (or a restarted one) may start its stamps anew.
    {
      std::lock_guard lock(stamp_mutex_);
      last_stamp_.reset();
    }
    if (new_publisher_) new_publisher_();
  }
}

void PointsListener::on_sample_lost(fdds::DataReader*, const fdds::SampleLostStatus& status) {
  samples_lost_.store(static_cast<std::uint64_t>(status.total_count));
}

}  // namespace litamin2::daemon

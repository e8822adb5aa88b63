#include "litamin2/daemon/dds/points_listener.hpp"

#include "sensor_msgs/msg/PointCloud2.h"

#include <spdlog/spdlog.h>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>

namespace litamin2::daemon {

namespace fdds = eprosima::fastdds::dds;

PointsListener::PointsListener(std::string stream, StreamScheduler& scheduler,
                               StreamScheduler::Handle handle, StreamStats& stats,
                               dds::CloudConversionOptions options)
    : stream_(std::move(stream)),
      scheduler_(scheduler),
      handle_(handle),
      stats_(stats),
      options_(options) {}

void PointsListener::on_data_available(fdds::DataReader* reader) {
  sensor_msgs::msg::PointCloud2 msg;
  fdds::SampleInfo info;
  dds::CloudConversion conversion;
  while (reader->take_next_sample(&msg, &info) == ReturnCode_t::RETCODE_OK) {
    if (!info.valid_data) continue;
    const auto arrival = std::chrono::steady_clock::now();
    if (dds::from_pointcloud2(msg, options_, conversion) != dds::CloudError::kNone) {
      stats_.record_bad_message();
      if (const auto suppressed = bad_message_log_.allow())
        spdlog::warn("stream {}: dropped a bad PointCloud2 ({}: {}){}", stream_,
                     dds::to_string(conversion.error), conversion.message,
                     *suppressed ? fmt::format(" and {} more since the last report", *suppressed)
                                 : std::string());
      continue;
    }
    Frame frame;
    frame.cloud = std::move(conversion.cloud);
    conversion.cloud = PointCloud();
    frame.stamp = {msg.header().stamp().sec(), msg.header().stamp().nanosec()};
    frame.frame_id = msg.header().frame_id();
    frame.arrival = arrival;
    frame.sequence = sequence_.fetch_add(1);
    stats_.record_received();
    scheduler_.submit(handle_, std::move(frame));
  }
}

void PointsListener::on_subscription_matched(fdds::DataReader*,
                                             const fdds::SubscriptionMatchedStatus& info) {
  spdlog::info("stream {}: {} publisher(s) matched", stream_, info.current_count);
}

void PointsListener::on_sample_lost(fdds::DataReader*, const fdds::SampleLostStatus& status) {
  samples_lost_.store(static_cast<std::uint64_t>(status.total_count));
}

}  // namespace litamin2::daemon

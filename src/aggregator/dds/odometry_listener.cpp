#include "litamin2/aggregator/dds/odometry_listener.hpp"

#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>

#include "litamin2/dds/checked_type.hpp"
#include "litamin2/dds/odometry_conversion.hpp"

#include <spdlog/spdlog.h>

namespace litamin2::aggregator {

namespace fdds = eprosima::fastdds::dds;

void OdometryListener::on_data_available(fdds::DataReader* reader) {
  nav_msgs::msg::Odometry msg;
  fdds::SampleInfo info;
  const auto reject = [&](const char* what, const std::string& detail) {
    relay_.reject(stream_);
    if (const auto suppressed = bad_log_.allow())
      spdlog::warn("stream {}: dropped a bad odometry message ({}: {}){}", stream_, what, detail,
                   *suppressed ? fmt::format(" and {} more since the last report", *suppressed)
                               : std::string());
  };
  // The reader's type is a dds::CheckedType: Fast DDS drops (inside take_next_sample) a sample
  // it could not deserialise; count those.
  dds::take_sample_failures();
  for (;;) {
    const bool taken = reader->take_next_sample(&msg, &info) == ReturnCode_t::RETCODE_OK;
    const dds::SampleFailures failed = dds::take_sample_failures();
    for (std::uint64_t i = 0; i < failed.count(); ++i)
      reject(dds::to_string(failed.last_error), failed.last_message);
    if (!taken) break;
    if (!info.valid_data) continue;
    const dds::OdometryConversion converted = dds::from_odometry(msg);
    if (!converted.ok()) {
      reject(dds::to_string(converted.error), converted.message);
      continue;
    }
    relay_.offer(stream_, std::move(msg));
    msg = nav_msgs::msg::Odometry();
  }
}

}  // namespace litamin2::aggregator

#include "litamin2/aggregator/dds/odometry_listener.hpp"

#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>

#include "litamin2/dds/odometry_conversion.hpp"

namespace litamin2::aggregator {

namespace fdds = eprosima::fastdds::dds;

void OdometryListener::on_data_available(fdds::DataReader* reader) {
  nav_msgs::msg::Odometry msg;
  fdds::SampleInfo info;
  while (reader->take_next_sample(&msg, &info) == ReturnCode_t::RETCODE_OK) {
    if (!info.valid_data) continue;
    if (!dds::from_odometry(msg).ok()) {
      relay_.reject(stream_);
      continue;
    }
    relay_.offer(stream_, std::move(msg));
    msg = nav_msgs::msg::Odometry();
  }
}

}  // namespace litamin2::aggregator

#include "litamin2/aggregator/dds/odometry_listener.hpp"

#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>

#include <cmath>

namespace litamin2::aggregator {

namespace fdds = eprosima::fastdds::dds;

namespace {

bool finite_pose(const geometry_msgs::msg::Pose& p) {
  const double v[] = {p.position().x(),    p.position().y(),    p.position().z(),
                      p.orientation().x(), p.orientation().y(), p.orientation().z(),
                      p.orientation().w()};
  for (double x : v)
    if (!std::isfinite(x)) return false;
  const double q = std::abs(p.orientation().x()) + std::abs(p.orientation().y()) +
                   std::abs(p.orientation().z()) + std::abs(p.orientation().w());
  return q > 0.0;
}

}  // namespace

void OdometryListener::on_data_available(fdds::DataReader* reader) {
  nav_msgs::msg::Odometry msg;
  fdds::SampleInfo info;
  while (reader->take_next_sample(&msg, &info) == ReturnCode_t::RETCODE_OK) {
    if (!info.valid_data) continue;
    if (!finite_pose(msg.pose().pose())) {
      relay_.reject(stream_);
      continue;
    }
    relay_.offer(stream_, std::move(msg));
    msg = nav_msgs::msg::Odometry();
  }
}

}  // namespace litamin2::aggregator

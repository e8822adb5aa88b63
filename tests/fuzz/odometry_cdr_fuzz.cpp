// Fuzz harness: a nav_msgs/Odometry as litamin2-aggregator receives it (rt/<stream>/odom), from
// raw CDR bytes through the reader's dds::CheckedType to dds::from_odometry.
// Properties: nothing throws; an accepted message has a valid pose (rotation, bounded
// translation) and finite covariances in both conventions.

#include "cdr_payload.hpp"
#include "fuzz_support.hpp"
#include "litamin2/dds/odometry_conversion.hpp"
#include "nav_msgs/msg/OdometryPubSubTypes.h"

using namespace litamin2;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static dds::CheckedType<nav_msgs::msg::OdometryPubSubType> type;
  nav_msgs::msg::Odometry msg;
  if (!fuzz::deserialize(type, data, size, msg)) return 0;
  const dds::OdometryConversion c = dds::from_odometry(msg);
  if (!c.ok()) {
    LITAMIN2_FUZZ_CHECK(!c.message.empty(), "rejected with a reason");
    return 0;
  }
  fuzz::check_pose(c.sample.pose);
  fuzz::accepted() = true;
  LITAMIN2_FUZZ_CHECK(!checks::covariance_error<6>(c.sample.ros_covariance), "ROS covariance");
  LITAMIN2_FUZZ_CHECK(c.sample.left_covariance.allFinite(), "left covariance finite");
  return 0;
}

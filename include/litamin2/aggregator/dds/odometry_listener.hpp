#pragma once
/// The reader listener of one stream's rt/<stream>/odom: takes each nav_msgs/Odometry, checks
/// it (dds::from_odometry; samples the reader's dds::CheckedType could not deserialise are
/// rejected too) and offers it to the MapOdometryRelay; a rejected message is counted by the
/// relay and logged at most once per second. Nothing else runs on the DDS thread (the relay's
/// offer only takes a short lock and never waits for the publisher).

#include "litamin2/aggregator/dds/map_odometry_relay.hpp"
#include "litamin2/service/log_rate_limiter.hpp"

#include <fastdds/dds/subscriber/DataReaderListener.hpp>

#include <string>

namespace litamin2::aggregator {

class OdometryListener : public eprosima::fastdds::dds::DataReaderListener {
 public:
  OdometryListener(std::string stream, MapOdometryRelay& relay)
      : stream_(std::move(stream)), relay_(relay) {}

  void on_data_available(eprosima::fastdds::dds::DataReader* reader) override;

 private:
  const std::string stream_;
  MapOdometryRelay& relay_;
  service::LogRateLimiter bad_log_;
};

}  // namespace litamin2::aggregator

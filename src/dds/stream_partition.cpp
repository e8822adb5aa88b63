#include "litamin2/dds/stream_partition.hpp"

#include <algorithm>

namespace litamin2::dds {

namespace fdds = eprosima::fastdds::dds;

fdds::PublisherQos stream_publisher_qos(const std::string& stream_id) {
  fdds::PublisherQos qos = fdds::PUBLISHER_QOS_DEFAULT;
  qos.partition().push_back(stream_id.c_str());
  return qos;
}

fdds::SubscriberQos every_stream_subscriber_qos() {
  fdds::SubscriberQos qos = fdds::SUBSCRIBER_QOS_DEFAULT;
  qos.partition().push_back("*");
  return qos;
}

bool stream_bound(const std::string& stream_id, const std::vector<std::string>& writer_partitions) {
  if (stream_id.empty()) return false;
  return std::find(writer_partitions.begin(), writer_partitions.end(), stream_id) !=
         writer_partitions.end();
}

}  // namespace litamin2::dds

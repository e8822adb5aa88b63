#include "litamin2/daemon/dds/publisher_discovery.hpp"

#include "litamin2/dds/qos.hpp"

namespace litamin2::daemon {

PublisherDiscovery::PublisherDiscovery(std::string type_name) : type_name_(std::move(type_name)) {}

void PublisherDiscovery::on_publisher_discovery(
    eprosima::fastdds::dds::DomainParticipant*,
    eprosima::fastrtps::rtps::WriterDiscoveryInfo&& info) {
  if (info.status != eprosima::fastrtps::rtps::WriterDiscoveryInfo::DISCOVERED_WRITER) return;
  DiscoveredWriter writer;
  writer.type = info.info.typeName().to_string();
  if (writer.type != type_name_) return;
  writer.topic = info.info.topicName().to_string();
  writer.reliable = dds::writer_is_reliable(info);
  std::lock_guard lock(mutex_);
  pending_.push_back(std::move(writer));
}

std::vector<DiscoveredWriter> PublisherDiscovery::take() {
  std::lock_guard lock(mutex_);
  std::vector<DiscoveredWriter> out;
  out.swap(pending_);
  return out;
}

}  // namespace litamin2::daemon

#include "litamin2/daemon/dds/publisher_discovery.hpp"

#include "litamin2/dds/qos.hpp"

#include <sstream>

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

void PublisherDiscovery::on_participant_discovery(
    eprosima::fastdds::dds::DomainParticipant*,
    eprosima::fastrtps::rtps::ParticipantDiscoveryInfo&& info) {
  using Info = eprosima::fastrtps::rtps::ParticipantDiscoveryInfo;
  ParticipantEvent event;
  std::ostringstream guid;
  guid << info.info.m_guid.guidPrefix;
  event.participant = guid.str();
  switch (info.status) {
    case Info::DISCOVERED_PARTICIPANT:
    case Info::CHANGED_QOS_PARTICIPANT: {
      const auto& data = info.info.m_userData.data_vec();
      event.user_data.assign(data.begin(), data.end());
      break;
    }
    case Info::REMOVED_PARTICIPANT:
    case Info::DROPPED_PARTICIPANT:
      event.alive = false;
      break;
  }
  std::lock_guard lock(mutex_);
  participants_.push_back(std::move(event));
}

std::vector<ParticipantEvent> PublisherDiscovery::take_participants() {
  std::lock_guard lock(mutex_);
  std::vector<ParticipantEvent> out;
  out.swap(participants_);
  return out;
}

std::vector<DiscoveredWriter> PublisherDiscovery::take() {
  std::lock_guard lock(mutex_);
  std::vector<DiscoveredWriter> out;
  out.swap(pending_);
  return out;
}

}  // namespace litamin2::daemon

#pragma once
/// Collects the DDS writers that discovery reports (topic, type, reliability) for the main
/// loop, which creates readers and trackers for them: Fast DDS calls the listener on its
/// discovery thread, where creating entities is not safe, so the listener only records. It
/// also records the participants that appear and disappear, with their USER_DATA, for the
/// daemons' membership (membership.hpp).

#include <fastdds/dds/domain/DomainParticipantListener.hpp>

#include <mutex>
#include <string>
#include <vector>

namespace litamin2::daemon {

/// A writer that appeared.
struct DiscoveredWriter {
  std::string topic;
  std::string type;
  bool reliable = false;
};

/// A participant that appeared (or changed its QoS) or left (removed, or its lease expired).
struct ParticipantEvent {
  /// Its GUID prefix, as text.
  std::string participant;
  bool alive = true;
  /// Its USER_DATA as bytes (alive only).
  std::string user_data;
};

class PublisherDiscovery : public eprosima::fastdds::dds::DomainParticipantListener {
 public:
  /// Only writers of `type_name` are recorded.
  explicit PublisherDiscovery(std::string type_name);

  void on_publisher_discovery(eprosima::fastdds::dds::DomainParticipant* participant,
                              eprosima::fastrtps::rtps::WriterDiscoveryInfo&& info) override;

  void on_participant_discovery(eprosima::fastdds::dds::DomainParticipant* participant,
                                eprosima::fastrtps::rtps::ParticipantDiscoveryInfo&& info) override;

  /// The writers discovered since the last call.
  std::vector<DiscoveredWriter> take();
  /// The participant events since the last call, in order.
  std::vector<ParticipantEvent> take_participants();

 private:
  const std::string type_name_;
  std::mutex mutex_;
  std::vector<DiscoveredWriter> pending_;
  std::vector<ParticipantEvent> participants_;
};

}  // namespace litamin2::daemon

#pragma once
/// Collects the DDS writers that discovery reports (topic, type, reliability) for the main
/// loop, which creates readers and trackers for them: Fast DDS calls the listener on its
/// discovery thread, where creating entities is not safe, so the listener only records.

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

class PublisherDiscovery : public eprosima::fastdds::dds::DomainParticipantListener {
 public:
  /// Only writers of `type_name` are recorded.
  explicit PublisherDiscovery(std::string type_name);

  void on_publisher_discovery(eprosima::fastdds::dds::DomainParticipant* participant,
                              eprosima::fastrtps::rtps::WriterDiscoveryInfo&& info) override;

  /// The writers discovered since the last call.
  std::vector<DiscoveredWriter> take();

 private:
  const std::string type_name_;
  std::mutex mutex_;
  std::vector<DiscoveredWriter> pending_;
};

}  // namespace litamin2::daemon

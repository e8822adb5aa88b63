#pragma once
// Helpers of the in-process DaemonNode tests (tests/unit/daemon_*_test.cpp): a PointCloud2
// publisher on the loopback-only profile (UDP on 127.0.0.1 with unicast discovery, shared
// memory; no multicast), polling the node until its status meets a condition, a per-process
// DDS domain, and the process's memory from /proc/self/status.

#include "litamin2/config/daemon_config_yaml.hpp"
#include "litamin2/daemon/dds/daemon_node.hpp"
#include "litamin2/dds/participant_factory.hpp"
#include "litamin2/dds/qos.hpp"
#include "sensor_msgs/msg/PointCloud2PubSubTypes.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/topic/Topic.hpp>

#include <chrono>
#include <cstdint>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace litamin2::testing {

/// A PointCloud2 publisher on the loopback profile: reliable keep-all writers (write() blocks
/// while `depth` samples are unacknowledged, so nothing is lost).
class CloudPublisher {
 public:
  explicit CloudPublisher(int domain, const std::string& name = "daemon_test_publisher") {
    litamin2::dds::ParticipantConfig config;
    config.domain_id = static_cast<std::uint32_t>(domain);
    config.name = name;
    participant_ = litamin2::dds::create_participant(config);
    if (!participant_) return;
    type_ = eprosima::fastdds::dds::TypeSupport(new sensor_msgs::msg::PointCloud2PubSubType());
    type_.register_type(participant_.get());
    publisher_ = participant_->create_publisher(eprosima::fastdds::dds::PUBLISHER_QOS_DEFAULT);
  }
  eprosima::fastdds::dds::DataWriter* writer(const std::string& topic_name, int depth = 100) {
    eprosima::fastdds::dds::Topic*& topic = topics_[topic_name];
    if (!topic)
      topic = participant_->create_topic(topic_name, type_.get_type_name(),
                                         eprosima::fastdds::dds::TOPIC_QOS_DEFAULT);
    return publisher_->create_datawriter(topic, litamin2::dds::points_writer_qos(false, depth));
  }
  void remove(eprosima::fastdds::dds::DataWriter* writer) { publisher_->delete_datawriter(writer); }
  bool ok() const { return participant_ && publisher_; }

 private:
  litamin2::dds::ParticipantPtr participant_;
  eprosima::fastdds::dds::TypeSupport type_;
  eprosima::fastdds::dds::Publisher* publisher_ = nullptr;
  std::map<std::string, eprosima::fastdds::dds::Topic*> topics_;
};

inline bool matched(eprosima::fastdds::dds::DataWriter* writer) {
  eprosima::fastdds::dds::PublicationMatchedStatus status;
  writer->get_publication_matched_status(status);
  return status.current_count > 0;
}

inline const daemon::StreamStatus& find(const std::vector<daemon::StreamStatus>& all,
                                        const std::string& id) {
  for (const auto& s : all)
    if (s.id == id) return s;
  throw std::runtime_error("no stream " + id);
}

/// Polls the node until `condition(status)` holds or `timeout` passes.
template <class F>
bool poll_until(daemon::DaemonNode& node, F condition,
                std::chrono::milliseconds timeout = std::chrono::seconds(30)) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < deadline) {
    node.poll();
    if (condition(node.status())) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

inline daemon::DaemonConfig config_of(const std::string& yaml) {
  return daemon::daemon_config_from_yaml(YAML::Load(yaml));
}

/// A DDS domain of this process's own (200..231): the first, from pid % 32 on, whose lock file
/// (/tmp/litamin2_test_domain_<d>.lock, flock held until the process exits) no other running
/// process holds. Test processes run in parallel (ctest -j, other build trees on the machine)
/// then never share a domain while at most 32 run at once; a shared one made a test take
/// another test's samples (PartitionedPatches: 21 taken for 2). Beyond 32, pid-based.
inline int test_domain() {
  static const int domain = [] {
    const int start = static_cast<int>(getpid() % 32);
    for (int i = 0; i < 32; ++i) {
      const int d = 200 + (start + i) % 32;
      const std::string path = "/tmp/litamin2_test_domain_" + std::to_string(d) + ".lock";
      const int fd = ::open(path.c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0666);
      if (fd < 0) continue;
      if (::flock(fd, LOCK_EX | LOCK_NB) == 0) return d;  // the lock lives as long as the process
      ::close(fd);
    }
    return 200 + start;
  }();
  return domain;
}

/// A "VmRSS"/"VmHWM"/... line of /proc/self/status in kB (-1 if absent).
inline long proc_status_kb(const std::string& key) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.compare(0, key.size() + 1, key + ":") == 0)
      return std::stol(line.substr(key.size() + 1));
  return -1;
}

}  // namespace litamin2::testing

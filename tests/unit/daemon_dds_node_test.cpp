// DaemonNode over real DDS, loopback-only profile (UDP on 127.0.0.1 with unicast discovery,
// shared memory; no multicast): malformed PointCloud2 messages are counted and dropped without
// disturbing their stream or another one; a stream published faster than it is processed drops
// its oldest frames and counts them.

#include "litamin2/daemon/daemon_config.hpp"

#include <gtest/gtest.h>

#if LITAMIN2_DAEMON_HAS_DDS

#include "litamin2/daemon/dds/daemon_node.hpp"
#include "litamin2/dds/pointcloud2_conversion.hpp"
#include "litamin2/dds/qos.hpp"
#include "sensor_msgs/msg/PointCloud2PubSubTypes.h"
#include "support/synthetic_scene.hpp"

#include <yaml-cpp/yaml.h>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/topic/Topic.hpp>

#include <thread>

namespace fdds = eprosima::fastdds::dds;
using namespace litamin2;
using namespace litamin2::daemon;
using namespace std::chrono_literals;

namespace {

/// A test publisher of PointCloud2 topics on the loopback profile.
class CloudPublisher {
 public:
  explicit CloudPublisher(int domain) {
    litamin2::dds::ParticipantConfig config;
    config.domain_id = static_cast<std::uint32_t>(domain);
    config.name = "daemon_dds_node_test";
    participant_ = litamin2::dds::create_participant(config);
    type_ = fdds::TypeSupport(new sensor_msgs::msg::PointCloud2PubSubType());
    type_.register_type(participant_.get());
    publisher_ = participant_->create_publisher(fdds::PUBLISHER_QOS_DEFAULT);
  }
  fdds::DataWriter* writer(const std::string& topic_name) {
    auto* topic =
        participant_->create_topic(topic_name, type_.get_type_name(), fdds::TOPIC_QOS_DEFAULT);
    return publisher_->create_datawriter(topic, litamin2::dds::points_writer_qos(false, 100));
  }
  bool ok() const { return participant_ && publisher_; }

 private:
  litamin2::dds::ParticipantPtr participant_;
  fdds::TypeSupport type_;
  fdds::Publisher* publisher_ = nullptr;
};

bool matched(fdds::DataWriter* writer) {
  fdds::PublicationMatchedStatus status;
  writer->get_publication_matched_status(status);
  return status.current_count > 0;
}

const StreamStatus& find(const std::vector<StreamStatus>& all, const std::string& id) {
  for (const auto& s : all)
    if (s.id == id) return s;
  throw std::runtime_error("no stream " + id);
}

/// Polls the node until `condition(status)` holds or `timeout` passes.
template <class F>
bool poll_until(DaemonNode& node, F condition, std::chrono::milliseconds timeout = 30s) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < deadline) {
    node.poll();
    if (condition(node.status())) return true;
    std::this_thread::sleep_for(10ms);
  }
  return false;
}

sensor_msgs::msg::PointCloud2 scan_message(int i) {
  static const PointCloud scene = litamin2::testing::synthetic_scene(3, 20000);
  Eigen::Isometry3d sensor = Eigen::Isometry3d::Identity();
  sensor.translation().x() = 0.5 * i;
  return litamin2::dds::to_pointcloud2(litamin2::testing::transformed(scene, sensor.inverse()),
                                       100.0 + 0.1 * i, "lidar");
}

DaemonConfig config_of(const std::string& yaml) {
  return daemon_config_from_yaml(YAML::Load(yaml));
}

}  // namespace

TEST(DaemonNode, BadMessagesAreCountedAndDropped) {
  DaemonNode node(config_of(R"(
dds: {domain: 41, profile: loopback}
streams: [{id: dnode_good}, {id: dnode_bad}]
threads: 2
queue_depth: 100
)"));
  CloudPublisher publisher(41);
  ASSERT_TRUE(publisher.ok());
  fdds::DataWriter* good = publisher.writer("rt/dnode_good/points");
  fdds::DataWriter* bad = publisher.writer("rt/dnode_bad/points");
  ASSERT_TRUE(good && bad);
  ASSERT_TRUE(poll_until(node, [&](const auto& st) {
    return find(st, "dnode_good").reading && find(st, "dnode_bad").reading && matched(good) &&
           matched(bad);
  })) << "readers were not created / matched";

  std::vector<sensor_msgs::msg::PointCloud2> malformed;
  auto variant = [&](auto change) {
    sensor_msgs::msg::PointCloud2 msg = scan_message(0);
    change(msg);
    malformed.push_back(std::move(msg));
  };
  variant([](auto& m) { m.data().resize(m.data().size() - 5); });      // truncated
  variant([](auto& m) { m.point_step(8); });                           // z and intensity outside
  variant([](auto& m) { m.row_step(m.row_step() / 2); });              // row_step too small
  variant([](auto& m) { m.fields().erase(m.fields().begin() + 2); });  // no z
  variant([](auto& m) { m.fields()[0].datatype(5); });                 // x as INT32
  variant([](auto& m) { m.width(m.width() + 1); });                    // width vs data size
  variant([](auto& m) { m.fields()[1].offset(m.point_step()); });      // y past the point
  for (auto& msg : malformed) ASSERT_TRUE(bad->write(&msg));
  // The bad stream's tracker is untouched: its next good frames are processed normally.
  for (int i = 0; i < 2; ++i) {
    auto msg = scan_message(i);
    ASSERT_TRUE(bad->write(&msg));
  }
  constexpr int kGood = 8;
  for (int i = 0; i < kGood; ++i) {
    auto msg = scan_message(i);
    ASSERT_TRUE(good->write(&msg));
  }
  ASSERT_TRUE(poll_until(node,
                         [&](const auto& st) {
                           return find(st, "dnode_good").stats.frames_processed == kGood &&
                                  find(st, "dnode_bad").stats.frames_processed == 2 &&
                                  find(st, "dnode_bad").stats.bad_messages == malformed.size();
                         }))
      << "bad " << find(node.status(), "dnode_bad").stats.bad_messages << " processed "
      << find(node.status(), "dnode_bad").stats.frames_processed;
  const auto status = node.status();
  EXPECT_EQ(find(status, "dnode_good").stats.bad_messages, 0u);
  EXPECT_EQ(find(status, "dnode_good").counters.dropped, 0u);
  EXPECT_EQ(find(status, "dnode_bad").stats.frames_unregistered, 1u);  // only the first frame
  EXPECT_EQ(find(status, "dnode_good").stats.frames_unregistered, 1u);
  EXPECT_TRUE(node.shutdown().complete);
}

TEST(DaemonNode, OverloadDropsOldestFrames) {
  DaemonNode node(config_of(R"(
dds: {domain: 42, profile: loopback}
streams: [{id: dnode_fast}]
threads: 1
queue_depth: 2
shutdown_timeout_s: 5
)"));
  CloudPublisher publisher(42);
  fdds::DataWriter* writer = publisher.writer("rt/dnode_fast/points");
  ASSERT_TRUE(writer);
  ASSERT_TRUE(poll_until(
      node, [&](const auto& st) { return find(st, "dnode_fast").reading && matched(writer); }));
  constexpr int kFrames = 40;
  std::vector<sensor_msgs::msg::PointCloud2> messages;
  for (int i = 0; i < kFrames; ++i) messages.push_back(scan_message(i));
  for (auto& msg : messages) ASSERT_TRUE(writer->write(&msg));
  ASSERT_TRUE(poll_until(node, [&](const auto& st) {
    return find(st, "dnode_fast").stats.frames_received == kFrames;
  }));
  EXPECT_TRUE(node.shutdown().complete);
  const StreamStatus s = find(node.status(), "dnode_fast");
  EXPECT_GT(s.counters.dropped, 0u);
  EXPECT_EQ(s.stats.frames_processed + s.counters.dropped, static_cast<std::uint64_t>(kFrames));
  EXPECT_EQ(s.counters.submitted, static_cast<std::uint64_t>(kFrames));
}

#else

TEST(DaemonNode, NeedsTheDdsLayer) {
  GTEST_SKIP() << "built without the DDS layer";
}

#endif

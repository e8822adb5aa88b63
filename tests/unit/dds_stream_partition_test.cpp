/// The map patches' stream binding (dds/stream_partition.hpp, dds/writer_partitions.hpp): the
/// check itself, the partitions of discovered writers, and what Fast DDS 2.9 does with the
/// partitions over the loopback profile (a "*" reader matches every named partition, not the
/// default one; the sample's publication_handle is the writer the discovery announced).

#include "litamin2/dds/participant_factory.hpp"
#include "litamin2/dds/qos.hpp"
#include "litamin2/dds/stream_partition.hpp"
#include "litamin2/dds/writer_partitions.hpp"
#include "litamin2/msg/MapPatchPubSubTypes.h"
#include "support/daemon_dds.hpp"

#include <fastdds/rtps/builtin/data/WriterProxyData.h>
#include <fastdds/rtps/writer/WriterDiscoveryInfo.h>
#include <gtest/gtest.h>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include <chrono>
#include <thread>

namespace litamin2::dds {
namespace {

namespace fdds = eprosima::fastdds::dds;
namespace rtps = eprosima::fastrtps::rtps;
using Clock = std::chrono::steady_clock;

TEST(DdsStreamPartition, StreamBoundIsExactMembership) {
  EXPECT_TRUE(stream_bound("car_1_a", {"car_1_a"}));
  EXPECT_TRUE(stream_bound("car_1_b", {"car_1_a", "car_1_b"}));
  EXPECT_FALSE(stream_bound("car_2_x", {"car_1_a"}));
  // Patterns are not expanded: a writer in "*" or "car_1_*" binds no real stream id.
  EXPECT_FALSE(stream_bound("car_1_a", {"*"}));
  EXPECT_FALSE(stream_bound("car_1_a", {"car_1_*"}));
  EXPECT_FALSE(stream_bound("car_1_a", {"car_1_?"}));
  // The default partition binds nothing, not even an empty stream id.
  EXPECT_FALSE(stream_bound("car_1_a", {}));
  EXPECT_FALSE(stream_bound("", {}));
  EXPECT_FALSE(stream_bound("", {""}));
  // Case and prefixes matter.
  EXPECT_FALSE(stream_bound("Car_1_a", {"car_1_a"}));
  EXPECT_FALSE(stream_bound("car_1", {"car_1_a"}));
  EXPECT_FALSE(stream_bound("car_1_a_b", {"car_1_a"}));
}

TEST(DdsStreamPartition, PublisherAndSubscriberQos) {
  EXPECT_EQ(stream_publisher_qos("car_1_a").partition().names(),
            std::vector<std::string>{"car_1_a"});
  EXPECT_EQ(every_stream_subscriber_qos().partition().names(), std::vector<std::string>{"*"});
}

rtps::GUID_t guid(std::uint8_t participant, std::uint8_t entity) {
  rtps::GUID_t g;
  g.guidPrefix.value[0] = participant;
  g.entityId.value[3] = entity;
  g.entityId.value[2] = 0x02;  // a user writer
  return g;
}

void announce(WriterPartitions& writers, const rtps::GUID_t& g, const std::string& topic,
              std::vector<std::string> partitions,
              rtps::WriterDiscoveryInfo::DISCOVERY_STATUS status) {
  rtps::WriterProxyData data(4, 4);
  data.guid(g);
  data.topicName(topic);
  for (const std::string& p : partitions) data.m_qos.m_partition.push_back(p.c_str());
  rtps::WriterDiscoveryInfo info(data);
  info.status = status;
  writers.on_publisher_discovery(nullptr, std::move(info));
}

TEST(DdsStreamPartition, WriterPartitionsFollowDiscovery) {
  WriterPartitions writers("rt/litamin2/map_patches");
  const rtps::GUID_t a = guid(1, 1), b = guid(2, 1), other_topic = guid(3, 1);
  EXPECT_FALSE(writers.find(rtps::InstanceHandle_t(a)));
  announce(writers, a, "rt/litamin2/map_patches", {"car_1_a", "car_1_b"},
           rtps::WriterDiscoveryInfo::DISCOVERED_WRITER);
  announce(writers, b, "rt/litamin2/map_patches", {}, rtps::WriterDiscoveryInfo::DISCOVERED_WRITER);
  announce(writers, other_topic, "rt/car_1_a/odom", {"car_1_a"},
           rtps::WriterDiscoveryInfo::DISCOVERED_WRITER);
  EXPECT_EQ(writers.size(), 2u);
  ASSERT_TRUE(writers.find(rtps::InstanceHandle_t(a)));
  EXPECT_EQ(*writers.find(rtps::InstanceHandle_t(a)),
            (std::vector<std::string>{"car_1_a", "car_1_b"}));
  ASSERT_TRUE(writers.find(rtps::InstanceHandle_t(b)));
  EXPECT_TRUE(writers.find(rtps::InstanceHandle_t(b))->empty());
  EXPECT_FALSE(writers.find(rtps::InstanceHandle_t(other_topic)));
  // A partition change of a live writer replaces its entry.
  announce(writers, a, "rt/litamin2/map_patches", {"car_2_x"},
           rtps::WriterDiscoveryInfo::CHANGED_QOS_WRITER);
  EXPECT_EQ(*writers.find(rtps::InstanceHandle_t(a)), std::vector<std::string>{"car_2_x"});
  announce(writers, a, "rt/litamin2/map_patches", {}, rtps::WriterDiscoveryInfo::REMOVED_WRITER);
  EXPECT_FALSE(writers.find(rtps::InstanceHandle_t(a)));
  EXPECT_EQ(writers.size(), 1u);
}

/// A reader participant (partition "*", WriterPartitions as its listener) and writers in
/// given partitions, over the loopback profile.
class PartitionedPatches : public ::testing::Test {
 protected:
  void SetUp() override {
    ParticipantConfig config;
    config.domain_id = litamin2::testing::test_domain();
    std::string error;
    reader_participant_ = create_participant(config, &error, &writers_);
    ASSERT_TRUE(reader_participant_) << error;
    writer_participant_ = create_participant(config, &error);
    ASSERT_TRUE(writer_participant_) << error;
    for (auto* p : {reader_participant_.get(), writer_participant_.get()})
      ASSERT_EQ(type_.register_type(p), ReturnCode_t::RETCODE_OK);
    auto* topic =
        reader_participant_->create_topic(kTopic, type_.get_type_name(), fdds::TOPIC_QOS_DEFAULT);
    writer_topic_ =
        writer_participant_->create_topic(kTopic, type_.get_type_name(), fdds::TOPIC_QOS_DEFAULT);
    ASSERT_TRUE(topic && writer_topic_);
    auto* subscriber = reader_participant_->create_subscriber(every_stream_subscriber_qos());
    ASSERT_TRUE(subscriber);
    reader_ = subscriber->create_datareader(topic, map_patches_reader_qos());
    ASSERT_TRUE(reader_);
  }

  fdds::DataWriter* writer(const std::vector<std::string>& partitions) {
    fdds::PublisherQos qos = fdds::PUBLISHER_QOS_DEFAULT;
    for (const std::string& p : partitions) qos.partition().push_back(p.c_str());
    auto* publisher = writer_participant_->create_publisher(qos);
    return publisher ? publisher->create_datawriter(writer_topic_, map_patches_writer_qos(10))
                     : nullptr;
  }

  static bool matched(fdds::DataWriter* w, std::chrono::seconds within) {
    const auto deadline = Clock::now() + within;
    fdds::PublicationMatchedStatus status;
    while (Clock::now() < deadline) {
      w->get_publication_matched_status(status);
      if (status.current_count > 0) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return false;
  }

  static constexpr const char* kTopic = "rt/litamin2/map_patches";
  WriterPartitions writers_{kTopic};
  fdds::TypeSupport type_{new litamin2::msg::MapPatchPubSubType()};
  ParticipantPtr reader_participant_, writer_participant_;
  fdds::Topic* writer_topic_ = nullptr;
  fdds::DataReader* reader_ = nullptr;
};

TEST_F(PartitionedPatches, EveryNamedPartitionMatchesAndTheSampleNamesItsWriter) {
  fdds::DataWriter* a = writer({"car_1_a"});
  fdds::DataWriter* b = writer({"car_2_x"});
  ASSERT_TRUE(a && b);
  ASSERT_TRUE(matched(a, std::chrono::seconds(15)));
  ASSERT_TRUE(matched(b, std::chrono::seconds(15)));
  litamin2::msg::MapPatch msg;
  msg.stream_id("car_1_a");
  ASSERT_TRUE(a->write(&msg));
  msg.stream_id("car_1_a");  // car_2_x's writer naming a stream of car_1
  ASSERT_TRUE(b->write(&msg));

  std::map<std::string, int> bound_by_writer_partition;
  int taken = 0;
  const auto deadline = Clock::now() + std::chrono::seconds(15);
  while (taken < 2 && Clock::now() < deadline) {
    reader_->wait_for_unread_message(eprosima::fastrtps::Duration_t(0, 200000000));
    litamin2::msg::MapPatch received;
    fdds::SampleInfo info;
    while (reader_->take_next_sample(&received, &info) == ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) continue;
      ++taken;
      const auto partitions = writers_.find(info.publication_handle);
      ASSERT_TRUE(partitions) << "the sample's writer is unknown to discovery";
      ASSERT_EQ(partitions->size(), 1u);
      bound_by_writer_partition[partitions->front()] +=
          stream_bound(received.stream_id(), *partitions) ? 1 : 0;
    }
  }
  ASSERT_EQ(taken, 2);
  EXPECT_EQ(bound_by_writer_partition["car_1_a"], 1);
  EXPECT_EQ(bound_by_writer_partition["car_2_x"], 0);
}

TEST_F(PartitionedPatches, TheDefaultPartitionDoesNotMatchTheStarReader) {
  fdds::DataWriter* unpartitioned = writer({});
  fdds::DataWriter* named = writer({"car_1_a"});
  ASSERT_TRUE(unpartitioned && named);
  // The named writer matching shows that discovery ran; the default one stays unmatched.
  ASSERT_TRUE(matched(named, std::chrono::seconds(15)));
  EXPECT_FALSE(matched(unpartitioned, std::chrono::seconds(2)));
}

}  // namespace
}  // namespace litamin2::dds

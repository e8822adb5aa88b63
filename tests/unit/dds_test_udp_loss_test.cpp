/// The test-only lossy UDP transport (test_udp_loss.hpp): the percentage's validation, the
/// transports it makes, and what it does to real traffic: a reliable writer still delivers
/// every sample through a lossy link, and a participant that drops everything it sends
/// delivers nothing (so the loss is not bypassed through shared memory).

#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>

#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastdds/rtps/transport/UDPv6TransportDescriptor.h>
#include <fastdds/rtps/transport/shared_mem/SharedMemTransportDescriptor.h>
#include <fastdds/rtps/transport/test_UDPv4TransportDescriptor.h>
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include "litamin2/dds/participant_factory.hpp"
#include "litamin2/dds/pointcloud2_conversion.hpp"
#include "litamin2/dds/qos.hpp"
#include "litamin2/dds/test_udp_loss.hpp"
#include "litamin2/service/topic_names.hpp"
#include "sensor_msgs/msg/PointCloud2PubSubTypes.h"

namespace litamin2::dds {
namespace {

namespace fdds = eprosima::fastdds::dds;
namespace frtps = eprosima::fastdds::rtps;

std::uint32_t test_domain() {
  return 100 + static_cast<std::uint32_t>(getpid() + 37) % 100;
}

/// Sets kTestUdpLossEnv for the scope.
struct LossEnv {
  explicit LossEnv(const char* value) { setenv(kTestUdpLossEnv, value, 1); }
  ~LossEnv() { unsetenv(kTestUdpLossEnv); }
  LossEnv(const LossEnv&) = delete;
  LossEnv& operator=(const LossEnv&) = delete;
};

TEST(TestUdpLoss, ParsesIntegerPercentagesOnly) {
  EXPECT_EQ(parse_test_udp_loss_percent("0"), 0);
  EXPECT_EQ(parse_test_udp_loss_percent("10"), 10);
  EXPECT_EQ(parse_test_udp_loss_percent("100"), 100);
  EXPECT_EQ(parse_test_udp_loss_percent("007"), 7);
  for (const char* bad : {"", "101", "-1", "+5", "10%", " 10", "10 ", "1.5", "abc", "1000"}) {
    std::string error;
    EXPECT_FALSE(parse_test_udp_loss_percent(bad, &error)) << bad;
    EXPECT_NE(error.find(kTestUdpLossEnv), std::string::npos) << error;
    EXPECT_NE(error.find("0..100"), std::string::npos) << error;
  }
}

TEST(TestUdpLoss, EnvironmentUnsetMeansOff) {
  unsetenv(kTestUdpLossEnv);
  std::string error = "stale";
  EXPECT_FALSE(test_udp_loss_from_env(&error));
  EXPECT_TRUE(error.empty());
  {
    LossEnv env("");
    EXPECT_FALSE(test_udp_loss_from_env(&error));
    EXPECT_TRUE(error.empty());
  }
  {
    LossEnv env("25");
    EXPECT_EQ(test_udp_loss_from_env(&error), 25);
  }
  {
    LossEnv env("ten");
    EXPECT_FALSE(test_udp_loss_from_env(&error));
    EXPECT_NE(error.find("'ten'"), std::string::npos) << error;
  }
}

TEST(TestUdpLoss, LoopbackProfileKeepsItsWhitelistAndBuffersAndLosesShm) {
  ParticipantConfig config;
  config.socket_buffer_bytes = 3u << 20;
  auto qos = participant_qos(config);
  ASSERT_TRUE(apply_test_udp_loss(qos, 10));
  EXPECT_FALSE(qos.transport().use_builtin_transports);
  ASSERT_EQ(qos.transport().user_transports.size(), 1u);
  const auto lossy = std::dynamic_pointer_cast<frtps::test_UDPv4TransportDescriptor>(
      qos.transport().user_transports[0]);
  ASSERT_TRUE(lossy);
  ASSERT_EQ(lossy->interfaceWhiteList.size(), 1u);
  EXPECT_EQ(lossy->interfaceWhiteList[0], "127.0.0.1");
  EXPECT_EQ(lossy->sendBufferSize, 3u << 20);
  EXPECT_EQ(lossy->receiveBufferSize, 3u << 20);
  EXPECT_EQ(lossy->maxInitialPeersRange, 32u);
  // Random drops through the filters, not Fast DDS's deterministic every-N-th percentages.
  EXPECT_EQ(lossy->dropDataMessagesPercentage, 0);
  EXPECT_EQ(lossy->percentageOfMessagesToDrop, 0);
  ASSERT_TRUE(lossy->drop_data_messages_filter_ && lossy->drop_data_frag_messages_filter_ &&
              lossy->drop_heartbeat_messages_filter_ && lossy->drop_ack_nack_messages_filter_);
  const auto before = test_udp_loss_counts();
  eprosima::fastrtps::rtps::CDRMessage_t message(64);
  int dropped = 0;
  for (int i = 0; i < 2000; ++i) dropped += lossy->drop_heartbeat_messages_filter_(message);
  const auto after = test_udp_loss_counts();
  EXPECT_EQ(after.heartbeat.seen - before.heartbeat.seen, 2000u);
  EXPECT_EQ(after.heartbeat.dropped - before.heartbeat.dropped, static_cast<unsigned>(dropped));
  EXPECT_GT(dropped, 120);  // 10 % of 2000: 200 +- 13.4 (1 sigma)
  EXPECT_LT(dropped, 280);
  EXPECT_EQ(after.data.seen, before.data.seen);
  // Unicast discovery on the loopback peer is untouched.
  EXPECT_EQ(qos.wire_protocol().builtin.initialPeersList.size(), 1u);
  EXPECT_TRUE(qos.wire_protocol().builtin.metatrafficMulticastLocatorList.empty());
}

TEST(TestUdpLoss, BuiltinTransportsBecomeOneLossyUdp) {
  ParticipantConfig config;
  config.transport = TransportProfile::kDefault;
  auto qos = participant_qos(config);
  ASSERT_TRUE(qos.transport().use_builtin_transports);
  ASSERT_TRUE(apply_test_udp_loss(qos, 0));
  EXPECT_FALSE(qos.transport().use_builtin_transports);
  ASSERT_EQ(qos.transport().user_transports.size(), 1u);
  EXPECT_TRUE(std::dynamic_pointer_cast<frtps::test_UDPv4TransportDescriptor>(
      qos.transport().user_transports[0]));
}

TEST(TestUdpLoss, RefusesAParticipantWithoutUdpv4) {
  fdds::DomainParticipantQos qos;
  qos.transport().use_builtin_transports = false;
  qos.transport().user_transports.push_back(std::make_shared<frtps::UDPv6TransportDescriptor>());
  std::string error;
  EXPECT_FALSE(apply_test_udp_loss(qos, 10, &error));
  EXPECT_NE(error.find("no UDPv4 transport"), std::string::npos) << error;
  ASSERT_EQ(qos.transport().user_transports.size(), 1u);  // untouched
}

TEST(TestUdpLoss, CreateParticipantRefusesABadValue) {
  LossEnv env("12.5");
  std::string error;
  EXPECT_FALSE(create_participant(ParticipantConfig{}, &error));
  EXPECT_NE(error.find(kTestUdpLossEnv), std::string::npos) << error;
}

/// Publishes `count` scans of `points` points (fragmented) from one participant to another,
/// both created with kTestUdpLossEnv = `percent`, reliable keep-all; returns how many arrived,
/// in order, within `seconds`.
int lossy_round_trip(const char* percent, int count, int points, int seconds) {
  LossEnv env(percent);
  ParticipantConfig config;
  config.domain_id = test_domain();
  std::string error;
  ParticipantPtr pub_participant = create_participant(config, &error);
  ParticipantPtr sub_participant = create_participant(config, &error);
  EXPECT_TRUE(pub_participant && sub_participant) << error;
  if (!pub_participant || !sub_participant) return -1;

  const std::string topic_name = service::points_topic("lossy_stream");
  fdds::TypeSupport type(new sensor_msgs::msg::PointCloud2PubSubType());
  type.register_type(pub_participant.get());
  type.register_type(sub_participant.get());
  auto* pub_topic =
      pub_participant->create_topic(topic_name, type.get_type_name(), fdds::TOPIC_QOS_DEFAULT);
  auto* sub_topic =
      sub_participant->create_topic(topic_name, type.get_type_name(), fdds::TOPIC_QOS_DEFAULT);
  auto* writer = pub_participant->create_publisher(fdds::PUBLISHER_QOS_DEFAULT)
                     ->create_datawriter(pub_topic, points_writer_qos(false, count));
  auto* reader = sub_participant->create_subscriber(fdds::SUBSCRIBER_QOS_DEFAULT)
                     ->create_datareader(sub_topic, points_reader_qos(true, count));
  EXPECT_TRUE(writer && reader);
  if (!writer || !reader) return -1;

  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
  fdds::PublicationMatchedStatus matched;
  while (std::chrono::steady_clock::now() < deadline) {
    writer->get_publication_matched_status(matched);
    if (matched.current_count > 0) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  PointCloud cloud;
  for (int i = 0; i < points; ++i) cloud.points.emplace_back(0.01f * i, 1.0f, 2.0f);
  for (int k = 0; k < count; ++k) {
    auto msg = to_pointcloud2(cloud, Stamp::from_seconds(k), "lossy_stream");
    writer->write(&msg);
  }
  int received = 0;
  sensor_msgs::msg::PointCloud2 sample;
  fdds::SampleInfo info;
  while (received < count && std::chrono::steady_clock::now() < deadline) {
    reader->wait_for_unread_message(eprosima::fastrtps::Duration_t(0, 100000000));
    while (reader->take_next_sample(&sample, &info) == ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) continue;
      EXPECT_EQ(sample.header().stamp().sec(), received) << "out of order or duplicated";
      EXPECT_EQ(from_pointcloud2(sample).cloud.size(), static_cast<std::size_t>(points));
      ++received;
    }
  }
  return received;
}

TEST(TestUdpLoss, ReliableDeliveryCompletesThroughALossyLink) {
  // 20 scans of ~160 kB (3 DATA_FRAGs each) with 20 % of every kind of message dropped.
  const auto before = test_udp_loss_counts();
  EXPECT_EQ(lossy_round_trip("20", 20, 10000, 60), 20);
  const auto after = test_udp_loss_counts();
  const auto frags = after.data_frag.seen - before.data_frag.seen;
  const auto lost = after.data_frag.dropped - before.data_frag.dropped;
  std::printf("DATA_FRAG: %llu of %llu dropped; %s\n", static_cast<unsigned long long>(lost),
              static_cast<unsigned long long>(frags), to_string(after).c_str());
  EXPECT_GE(frags, 60u);  // 20 x 3 fragments at least once
  EXPECT_GT(lost, 0u);    // dropped, and delivered anyway
}

TEST(TestUdpLoss, EverythingDroppedDeliversNothing) {
  // Both participants drop all they send, and there is no shared memory to bypass it.
  EXPECT_EQ(lossy_round_trip("100", 3, 1000, 3), 0);
}

}  // namespace
}  // namespace litamin2::dds

/// Participant profiles, QoS helpers, and a PointCloud2 round trip through Fast DDS on the
/// loopback-only profile (built-in and XML): traffic stays on 127.0.0.1 / shared memory.

#include <gtest/gtest.h>
#include <spdlog/sinks/ringbuffer_sink.h>
#include <spdlog/spdlog.h>

#include <unistd.h>
#include <fastdds/dds/log/Log.hpp>

#include <chrono>
#include <thread>

#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include "diagnostic_msgs/msg/DiagnosticArrayPubSubTypes.h"
#include "litamin2/dds/participant_factory.hpp"
#include "litamin2/dds/pointcloud2_conversion.hpp"
#include "litamin2/dds/qos.hpp"
#include "litamin2/msg/MapPatchPubSubTypes.h"
#include "litamin2/service/topic_names.hpp"
#include "nav_msgs/msg/OdometryPubSubTypes.h"
#include "sensor_msgs/msg/PointCloud2PubSubTypes.h"

namespace litamin2::dds {
namespace {

namespace fdds = eprosima::fastdds::dds;

/// A domain id per test process, so that concurrent test runs do not see each other.
std::uint32_t test_domain() {
  return 100 + static_cast<std::uint32_t>(getpid()) % 100;
}

TEST(DdsParticipant, ParseProfile) {
  EXPECT_EQ(parse_participant_profile("loopback")->transport, TransportProfile::kLoopback);
  EXPECT_EQ(parse_participant_profile("shm")->transport, TransportProfile::kShm);
  EXPECT_EQ(parse_participant_profile("default")->transport, TransportProfile::kDefault);
  auto xml = parse_participant_profile("config/dds/loopback.xml");
  ASSERT_TRUE(xml);
  EXPECT_EQ(xml->transport, TransportProfile::kXml);
  EXPECT_EQ(xml->xml_file, "config/dds/loopback.xml");
  EXPECT_EQ(xml->xml_profile, "litamin2");
  xml = parse_participant_profile("/etc/x.xml:mine");
  ASSERT_TRUE(xml);
  EXPECT_EQ(xml->xml_file, "/etc/x.xml");
  EXPECT_EQ(xml->xml_profile, "mine");
  std::string error;
  EXPECT_FALSE(parse_participant_profile("udp", &error));
  EXPECT_NE(error.find("loopback"), std::string::npos);
  EXPECT_FALSE(parse_participant_profile("", &error));
  EXPECT_FALSE(parse_participant_profile("x.xml:", &error));
  EXPECT_STREQ(to_string(TransportProfile::kLoopback), "loopback");
}

TEST(DdsParticipant, LoopbackQosKeepsTrafficOnThisHost) {
  ParticipantConfig config;
  const auto qos = participant_qos(config);
  EXPECT_FALSE(qos.transport().use_builtin_transports);
  ASSERT_EQ(qos.transport().user_transports.size(), 2u);
  bool udp_found = false;
  for (const auto& t : qos.transport().user_transports) {
    if (auto udp =
            std::dynamic_pointer_cast<eprosima::fastdds::rtps::UDPv4TransportDescriptor>(t)) {
      udp_found = true;
      ASSERT_EQ(udp->interfaceWhiteList.size(), 1u);
      EXPECT_EQ(udp->interfaceWhiteList[0], "127.0.0.1");
      EXPECT_EQ(udp->receiveBufferSize, 4u << 20);
    }
  }
  EXPECT_TRUE(udp_found);
  const auto& builtin = qos.wire_protocol().builtin;
  EXPECT_EQ(builtin.initialPeersList.size(), 1u);
  EXPECT_TRUE(builtin.metatrafficMulticastLocatorList.empty());
  EXPECT_EQ(builtin.metatrafficUnicastLocatorList.size(), 1u);
  EXPECT_TRUE(qos.wire_protocol().default_multicast_locator_list.empty());
}

TEST(DdsParticipant, TopicQos) {
  EXPECT_EQ(points_reader_qos().reliability().kind, fdds::BEST_EFFORT_RELIABILITY_QOS);
  EXPECT_EQ(points_reader_qos(true).reliability().kind, fdds::RELIABLE_RELIABILITY_QOS);
  EXPECT_EQ(points_writer_qos().reliability().kind, fdds::RELIABLE_RELIABILITY_QOS);
  EXPECT_EQ(points_writer_qos().history().kind, fdds::KEEP_ALL_HISTORY_QOS);
  EXPECT_EQ(points_writer_qos(true).reliability().kind, fdds::BEST_EFFORT_RELIABILITY_QOS);
  EXPECT_EQ(odom_writer_qos().reliability().kind, fdds::RELIABLE_RELIABILITY_QOS);
  EXPECT_EQ(odom_writer_qos().history().kind, fdds::KEEP_LAST_HISTORY_QOS);
  EXPECT_EQ(map_patches_writer_qos(500).durability().kind, fdds::TRANSIENT_LOCAL_DURABILITY_QOS);
  EXPECT_EQ(map_patches_writer_qos(500).history().kind, fdds::KEEP_ALL_HISTORY_QOS);
  EXPECT_EQ(map_patches_writer_qos(500).resource_limits().max_samples_per_instance, 500);
  EXPECT_EQ(map_patches_reader_qos().durability().kind, fdds::TRANSIENT_LOCAL_DURABILITY_QOS);
  EXPECT_EQ(status_reader_qos().reliability().kind, fdds::RELIABLE_RELIABILITY_QOS);
}

// The writers a reader waits on in order (odometry, /tf, the exclusive hot-standby odometry)
// and the map-patch writers send heartbeats at their named periods, shorter than Fast DDS's
// default (3 s), which is what a sample lost on the link waited for before being resent.
TEST(DdsParticipant, RepairHeartbeatPeriods) {
  const auto period_ms = [](const fdds::DataWriterQos& qos) {
    const auto& period = qos.reliable_writer_qos().times.heartbeatPeriod;
    return static_cast<double>(period.seconds) * 1e3 + static_cast<double>(period.nanosec) / 1e6;
  };
  const double default_ms = period_ms(fdds::DATAWRITER_QOS_DEFAULT);
  EXPECT_DOUBLE_EQ(period_ms(odom_writer_qos()), kOdometryHeartbeatPeriodMs);
  EXPECT_DOUBLE_EQ(period_ms(exclusive_odom_writer_qos(2)), kOdometryHeartbeatPeriodMs);
  EXPECT_DOUBLE_EQ(period_ms(tf_writer_qos()), kOdometryHeartbeatPeriodMs);
  EXPECT_DOUBLE_EQ(period_ms(map_patches_writer_qos(500)), kMapPatchHeartbeatPeriodMs);
  EXPECT_LT(kOdometryHeartbeatPeriodMs, default_ms);
  EXPECT_LT(kMapPatchHeartbeatPeriodMs, default_ms);
  // Other writers keep the default (a status or a tile superseded by the next one).
  EXPECT_DOUBLE_EQ(period_ms(status_writer_qos()), default_ms);
}

TEST(DdsParticipant, Ros2TypeNames) {
  EXPECT_EQ(fdds::TypeSupport(new sensor_msgs::msg::PointCloud2PubSubType()).get_type_name(),
            "sensor_msgs::msg::dds_::PointCloud2_");
  EXPECT_EQ(fdds::TypeSupport(new nav_msgs::msg::OdometryPubSubType()).get_type_name(),
            "nav_msgs::msg::dds_::Odometry_");
  EXPECT_EQ(
      fdds::TypeSupport(new diagnostic_msgs::msg::DiagnosticArrayPubSubType()).get_type_name(),
      "diagnostic_msgs::msg::dds_::DiagnosticArray_");
  fdds::TypeSupport patch(new litamin2::msg::MapPatchPubSubType());
  EXPECT_EQ(patch.get_type_name(), "litamin2::msg::dds_::MapPatch_");
  EXPECT_TRUE(patch->m_isGetKeyDefined);
}

TEST(DdsParticipant, XmlProfileErrors) {
  ParticipantConfig config;
  config.transport = TransportProfile::kXml;
  config.xml_file = "/nonexistent/profile.xml";
  std::string error;
  EXPECT_FALSE(create_participant(config, &error));
  EXPECT_NE(error.find("/nonexistent/profile.xml"), std::string::npos);
  config.xml_file = LITAMIN2_SOURCE_DIR "/config/dds/loopback.xml";
  config.xml_profile = "no_such_profile";
  EXPECT_FALSE(create_participant(config, &error));
  EXPECT_NE(error.find("no_such_profile"), std::string::npos);
}

/// Publishes one large scan from `writer_config` to `reader_config` and checks it arrives
/// bit-identical.
void round_trip(const ParticipantConfig& writer_config, const ParticipantConfig& reader_config) {
  std::string error;
  ParticipantPtr pub_participant = create_participant(writer_config, &error);
  ASSERT_TRUE(pub_participant) << error;
  ParticipantPtr sub_participant = create_participant(reader_config, &error);
  ASSERT_TRUE(sub_participant) << error;

  const std::string topic_name = service::points_topic("test_stream");
  fdds::TypeSupport type(new sensor_msgs::msg::PointCloud2PubSubType());
  ASSERT_EQ(type.register_type(pub_participant.get()), ReturnCode_t::RETCODE_OK);
  ASSERT_EQ(type.register_type(sub_participant.get()), ReturnCode_t::RETCODE_OK);
  auto* pub_topic =
      pub_participant->create_topic(topic_name, type.get_type_name(), fdds::TOPIC_QOS_DEFAULT);
  auto* sub_topic =
      sub_participant->create_topic(topic_name, type.get_type_name(), fdds::TOPIC_QOS_DEFAULT);
  ASSERT_TRUE(pub_topic && sub_topic);
  auto* publisher = pub_participant->create_publisher(fdds::PUBLISHER_QOS_DEFAULT);
  auto* subscriber = sub_participant->create_subscriber(fdds::SUBSCRIBER_QOS_DEFAULT);
  auto* writer = publisher->create_datawriter(pub_topic, points_writer_qos());
  auto* reader = subscriber->create_datareader(sub_topic, points_reader_qos(true));
  ASSERT_TRUE(writer && reader);

  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(15);
  fdds::PublicationMatchedStatus matched;
  while (std::chrono::steady_clock::now() < deadline) {
    writer->get_publication_matched_status(matched);
    if (matched.current_count > 0) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_GT(matched.current_count, 0) << "no match within 15 s";

  PointCloud cloud;
  for (int i = 0; i < 120000; ++i) {
    cloud.points.emplace_back(0.001f * static_cast<float>(i), std::sin(0.01f * i), 1.5f);
    cloud.intensities.push_back(static_cast<float>(i % 256));
  }
  auto msg = to_pointcloud2(cloud, Stamp::from_seconds(42.25), "test_stream");
  ASSERT_TRUE(writer->write(&msg));

  sensor_msgs::msg::PointCloud2 received;
  fdds::SampleInfo info;
  bool got = false;
  while (!got && std::chrono::steady_clock::now() < deadline) {
    reader->wait_for_unread_message(eprosima::fastrtps::Duration_t(0, 200000000));
    got = reader->take_next_sample(&received, &info) == ReturnCode_t::RETCODE_OK && info.valid_data;
  }
  ASSERT_TRUE(got) << "no sample within 15 s";
  EXPECT_EQ(received.header().frame_id(), "test_stream");
  const auto result = from_pointcloud2(received);
  ASSERT_TRUE(result.ok()) << result.message;
  ASSERT_EQ(result.cloud.size(), cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    ASSERT_EQ(result.cloud.points[i], cloud.points[i]) << i;
    ASSERT_EQ(result.cloud.intensities[i], cloud.intensities[i]) << i;
  }
}

TEST(DdsParticipant, LoopbackRoundTripOfALargeScan) {
  ParticipantConfig config;
  config.domain_id = test_domain();
  round_trip(config, config);
}

TEST(DdsParticipant, XmlLoopbackProfileTalksToBuiltinLoopback) {
  ParticipantConfig builtin;
  builtin.domain_id = test_domain();
  ParticipantConfig xml = builtin;
  xml.transport = TransportProfile::kXml;
  xml.xml_file = LITAMIN2_SOURCE_DIR "/config/dds/loopback.xml";
  round_trip(xml, builtin);
}

TEST(DdsParticipant, LogForwardingIsIdempotent) {
  // Fast DDS's errors reach spdlog's default logger exactly once, however often forwarding is
  // installed (a second console consumer or a second forwarder would duplicate them).
  auto sink = std::make_shared<spdlog::sinks::ringbuffer_sink_mt>(64);
  const auto previous = spdlog::default_logger();
  spdlog::set_default_logger(std::make_shared<spdlog::logger>("test", sink));
  forward_fastdds_log_to_spdlog();
  forward_fastdds_log_to_spdlog();
  EPROSIMA_LOG_ERROR(LITAMIN2_TEST, "forwarding marker 7f3a");
  eprosima::fastdds::dds::Log::Flush();
  spdlog::set_default_logger(previous);
  int forwarded = 0;
  for (const std::string& line : sink->last_formatted())
    if (line.find("fastdds [LITAMIN2_TEST] forwarding marker 7f3a") != std::string::npos)
      ++forwarded;
  EXPECT_EQ(forwarded, 1);
}

}  // namespace
}  // namespace litamin2::dds

/// The aggregator's patch listener over real DDS (loopback profile): a patch is kept only if its
/// stream id is a partition of the writer that sent it (dds/stream_partition.hpp); the others
/// are counted as stream_not_bound and never reach the queue.

#include "litamin2/aggregator/dds/patch_listener.hpp"
#include "litamin2/aggregator/patch_queue.hpp"
#include "litamin2/dds/map_patch_conversion.hpp"
#include "litamin2/dds/participant_factory.hpp"
#include "litamin2/dds/qos.hpp"
#include "litamin2/dds/stream_partition.hpp"
#include "litamin2/dds/writer_partitions.hpp"
#include "litamin2/msg/MapPatchPubSubTypes.h"
#include "support/daemon_dds.hpp"

#include <gtest/gtest.h>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include <chrono>
#include <functional>
#include <map>
#include <thread>

namespace litamin2::aggregator {
namespace {

namespace fdds = eprosima::fastdds::dds;
using Clock = std::chrono::steady_clock;

litamin2::msg::MapPatch patch(const std::string& stream, std::uint64_t id) {
  Keyframe kf;
  kf.key = {stream, id};
  kf.stamp = Stamp::from_seconds(100.0 + static_cast<double>(id));
  kf.covariance = Matrix6d::Identity() * 1e-4;
  kf.voxel_size = 1.0;
  for (int i = 0; i < 20; ++i) {
    Distribution d;
    d.mean = Eigen::Vector3d(i, 0.5 * i, 1.0);
    d.cov = Eigen::Matrix3d::Identity() * 0.1;
    d.count = 10;
    kf.distributions.push_back(d);
  }
  return dds::to_map_patch(kf, stream + "/odom");
}

bool wait_until(const std::function<bool()>& done, std::chrono::seconds within) {
  const auto deadline = Clock::now() + within;
  while (Clock::now() < deadline) {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return done();
}

struct Outcome {
  std::uint64_t received = 0;
  std::map<std::string, std::uint64_t> rejected;
  std::vector<Keyframe> queued;
};

/// One writer in partition `partition` sends a patch per entry of `streams` to a PatchListener
/// whose WriterPartitions records the writers of `recorded_topic`.
Outcome run(const std::string& recorded_topic, const std::string& partition,
            const std::vector<std::string>& streams) {
  const std::string topic_name = "rt/litamin2/map_patches";
  dds::WriterPartitions writers(recorded_topic);
  PatchQueue queue(100);
  PatchListener listener(queue, {}, &writers);
  Outcome out;

  dds::ParticipantConfig config;
  config.domain_id = litamin2::testing::test_domain();
  std::string error;
  dds::ParticipantPtr reader_participant = dds::create_participant(config, &error, &writers);
  EXPECT_TRUE(reader_participant) << error;
  dds::ParticipantPtr writer_participant = dds::create_participant(config, &error);
  EXPECT_TRUE(writer_participant) << error;
  if (!reader_participant || !writer_participant) return out;
  fdds::TypeSupport type(new litamin2::msg::MapPatchPubSubType());
  type.register_type(reader_participant.get());
  type.register_type(writer_participant.get());
  auto* reader_topic =
      reader_participant->create_topic(topic_name, type.get_type_name(), fdds::TOPIC_QOS_DEFAULT);
  auto* writer_topic =
      writer_participant->create_topic(topic_name, type.get_type_name(), fdds::TOPIC_QOS_DEFAULT);
  auto* subscriber = reader_participant->create_subscriber(dds::every_stream_subscriber_qos());
  auto* reader = subscriber->create_datareader(reader_topic, dds::map_patches_reader_qos(),
                                               &listener, fdds::StatusMask::data_available());
  auto* publisher = writer_participant->create_publisher(dds::stream_publisher_qos(partition));
  auto* writer = publisher->create_datawriter(writer_topic, dds::map_patches_writer_qos(10));
  EXPECT_TRUE(reader && writer);
  if (!reader || !writer) return out;
  EXPECT_TRUE(wait_until(
      [&] {
        fdds::PublicationMatchedStatus s;
        writer->get_publication_matched_status(s);
        return s.current_count > 0;
      },
      std::chrono::seconds(15)));
  std::uint64_t id = 0;
  for (const std::string& stream : streams) {
    litamin2::msg::MapPatch msg = patch(stream, id++);
    EXPECT_TRUE(writer->write(&msg));
  }
  EXPECT_TRUE(
      wait_until([&] { return listener.received() == streams.size(); }, std::chrono::seconds(15)))
      << listener.received() << " received";
  reader->set_listener(nullptr);
  out.received = listener.received();
  out.rejected = listener.rejected_by_reason();
  queue.pop_batch(out.queued, 100, std::chrono::milliseconds(100));
  return out;
}

TEST(AggregatorPatchBinding, APatchNamingAStreamOutsideItsWritersPartitionIsRejected) {
  // Its own stream, twice; another daemon's stream; its own again.
  const Outcome out =
      run("rt/litamin2/map_patches", "car_1_a", {"car_1_a", "car_1_a", "car_2_x", "car_1_a"});
  EXPECT_EQ(out.received, 4u);
  ASSERT_EQ(out.rejected.size(), 1u);
  EXPECT_EQ(out.rejected.at(dds::kStreamNotBound), 1u);
  ASSERT_EQ(out.queued.size(), 3u);
  for (const Keyframe& kf : out.queued) EXPECT_EQ(kf.key.stream, "car_1_a");
}

TEST(AggregatorPatchBinding, AWriterUnknownToDiscoveryBindsNoStream) {
  // The partitions recorded are another topic's: the patches' writer is unknown, so even
  // patches of its own partition are refused (the check fails closed).
  const Outcome out = run("rt/other", "car_1_a", {"car_1_a", "car_1_a"});
  EXPECT_EQ(out.received, 2u);
  ASSERT_EQ(out.rejected.size(), 1u);
  EXPECT_EQ(out.rejected.at(dds::kStreamNotBound), 2u);
  EXPECT_TRUE(out.queued.empty());
}

TEST(AggregatorPatchBinding, PatchesTakenTogetherAreQueuedInSourceTimestampOrder) {
  // Fast DDS takes by instance (key hash: vehicle_01's sorts before vehicle_00's); with one
  // writer per stream the listener restores the writers' order. Both samples are in the reader
  // before the listener runs (it is called by hand), as when streams start together.
  const std::string topic_name = "rt/litamin2/map_patches";
  dds::WriterPartitions writers(topic_name);
  PatchQueue queue(10);
  PatchListener listener(queue, {}, &writers);
  dds::ParticipantConfig config;
  config.domain_id = litamin2::testing::test_domain();
  std::string error;
  dds::ParticipantPtr reader_participant = dds::create_participant(config, &error, &writers);
  dds::ParticipantPtr writer_participant = dds::create_participant(config, &error);
  ASSERT_TRUE(reader_participant && writer_participant) << error;
  fdds::TypeSupport type(new litamin2::msg::MapPatchPubSubType());
  type.register_type(reader_participant.get());
  type.register_type(writer_participant.get());
  auto* reader_topic =
      reader_participant->create_topic(topic_name, type.get_type_name(), fdds::TOPIC_QOS_DEFAULT);
  auto* writer_topic =
      writer_participant->create_topic(topic_name, type.get_type_name(), fdds::TOPIC_QOS_DEFAULT);
  auto* subscriber = reader_participant->create_subscriber(dds::every_stream_subscriber_qos());
  auto* reader = subscriber->create_datareader(reader_topic, dds::map_patches_reader_qos());
  ASSERT_TRUE(reader);
  std::vector<fdds::DataWriter*> stream_writers;
  for (const char* stream : {"vehicle_00", "vehicle_01"}) {
    auto* publisher = writer_participant->create_publisher(dds::stream_publisher_qos(stream));
    stream_writers.push_back(
        publisher->create_datawriter(writer_topic, dds::map_patches_writer_qos(10)));
    ASSERT_TRUE(stream_writers.back());
  }
  ASSERT_TRUE(wait_until(
      [&] {
        fdds::SubscriptionMatchedStatus s;
        reader->get_subscription_matched_status(s);
        return s.current_count == 2;
      },
      std::chrono::seconds(15)));
  for (std::size_t i = 0; i < 2; ++i) {
    litamin2::msg::MapPatch msg = patch(i == 0 ? "vehicle_00" : "vehicle_01", 0);
    ASSERT_TRUE(stream_writers[i]->write(&msg));
    std::this_thread::sleep_for(std::chrono::milliseconds(5));  // distinct source timestamps
  }
  ASSERT_TRUE(
      wait_until([&] { return reader->get_unread_count() == 2; }, std::chrono::seconds(15)));
  listener.on_data_available(reader);
  std::vector<Keyframe> queued;
  queue.pop_batch(queued, 10, std::chrono::milliseconds(100));
  ASSERT_EQ(queued.size(), 2u);
  EXPECT_EQ(queued[0].key.stream, "vehicle_00");
  EXPECT_EQ(queued[1].key.stream, "vehicle_01");
}

}  // namespace
}  // namespace litamin2::aggregator

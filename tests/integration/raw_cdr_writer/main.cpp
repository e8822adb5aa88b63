// raw_cdr_writer: publishes hand-corrupted CDR payloads under the project's type names, as an
// attacker (or a buggy client of another vendor) would: a valid PointCloud2 / MapPatch /
// Odometry is serialised by the generated code, then corrupted, and written as raw bytes by a
// TopicDataType that registers the same type name (Fast DDS matches types by name).
//   --malformation valid          the bytes as serialised (the raw path itself works)
//                  bad_bool       PointCloud2: is_dense (the last byte) set to 2
//                  truncated      the payload cut in the middle of its last sequence
//                  length_beyond  the length of the last sequence (data / distributions) set to
//                                 0x7fffffff, far beyond the payload
// --distributions N makes a patch of N distributions (40 bytes each on the wire).
// --partition P (repeatable) sets the publisher's partitions; a patch's default is its --stream
// (as litamin2d publishes, dds/stream_partition.hpp), the other types' the default partition.
// Waits for a reader to match, writes --count samples (reliable, keep-all), waits until they
// are acknowledged and exits 0; exit 1 when no reader matched within --timeout.

#include "litamin2/dds/map_patch_conversion.hpp"
#include "litamin2/dds/odometry_conversion.hpp"
#include "litamin2/dds/participant_factory.hpp"
#include "litamin2/dds/pointcloud2_conversion.hpp"
#include "litamin2/dds/qos.hpp"
#include "litamin2/msg/MapPatchPubSubTypes.h"
#include "nav_msgs/msg/OdometryPubSubTypes.h"
#include "sensor_msgs/msg/PointCloud2PubSubTypes.h"
#include "support/probe_participant.hpp"

#include <CLI/CLI.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TopicDataType.hpp>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <thread>
#include <vector>

namespace fdds = eprosima::fastdds::dds;
namespace rtps = eprosima::fastrtps::rtps;
using namespace litamin2;

namespace {

struct RawSample {
  std::vector<unsigned char> bytes;
  rtps::InstanceHandle_t key;
};

/// Writes RawSample::bytes verbatim (encapsulation header included) under `name`.
class RawType : public fdds::TopicDataType {
 public:
  RawType(const std::string& name, bool keyed) {
    setName(name.c_str());
    m_typeSize = 4;
    m_isGetKeyDefined = keyed;
  }
  bool serialize(void* data, rtps::SerializedPayload_t* payload) override {
    const auto* s = static_cast<RawSample*>(data);
    if (payload->max_size < s->bytes.size()) return false;
    std::memcpy(payload->data, s->bytes.data(), s->bytes.size());
    payload->length = static_cast<std::uint32_t>(s->bytes.size());
    payload->encapsulation = CDR_LE;
    return true;
  }
  bool deserialize(rtps::SerializedPayload_t*, void*) override { return false; }
  std::function<std::uint32_t()> getSerializedSizeProvider(void* data) override {
    const auto* s = static_cast<RawSample*>(data);
    return [s] { return static_cast<std::uint32_t>(s->bytes.size()); };
  }
  void* createData() override { return new RawSample(); }
  void deleteData(void* data) override { delete static_cast<RawSample*>(data); }
  bool getKey(void* data, rtps::InstanceHandle_t* handle, bool) override {
    *handle = static_cast<RawSample*>(data)->key;
    return true;
  }
};

/// The serialised bytes of `msg` by its generated type, and its key.
template <class PubSubType, class Msg>
RawSample serialise(Msg& msg) {
  PubSubType type;
  rtps::SerializedPayload_t payload(type.getSerializedSizeProvider(&msg)());
  type.serialize(&msg, &payload);
  RawSample s;
  s.bytes.assign(payload.data, payload.data + payload.length);
  if (type.m_isGetKeyDefined) type.getKey(&msg, &s.key, false);
  return s;
}

void put_u32(std::vector<unsigned char>& b, std::size_t offset, std::uint32_t v) {
  std::memcpy(b.data() + offset, &v, 4);  // little-endian host, CDR_LE payload
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"raw_cdr_writer: publishes corrupted CDR samples"};
  std::string type = "points", topic, stream = "raw_stream", malformation = "bad_bool";
  litamin2::testing::ProbeParticipantOptions dds_options;
  int count = 5;
  int distributions = 100;
  std::vector<std::string> partitions;
  double timeout_s = 30.0;
  app.add_option("--type", type, "points | patch | odom")->required();
  app.add_option("--topic", topic,
                 "default: rt/<stream>/points, rt/litamin2/map_patches, "
                 "rt/<stream>/odom");
  app.add_option("--stream", stream);
  app.add_option("--malformation", malformation, "valid | bad_bool | truncated | length_beyond");
  app.add_option("--count", count);
  app.add_option("--distributions", distributions, "a patch's distributions (its size)");
  app.add_option("--partition", partitions, "the publisher's partitions");
  dds_options.add_to(app);
  app.add_option("--timeout", timeout_s);
  CLI11_PARSE(app, argc, argv);

  RawSample sample;
  std::string type_name;
  std::size_t last_sequence_length = 0;  // offset of the last sequence's length field
  std::size_t element_bytes = 1;
  if (type == "points") {
    PointCloud cloud;
    for (int i = 0; i < 1000; ++i) cloud.points.emplace_back(0.01f * i, 1.0f, 2.0f);
    auto msg = litamin2::dds::to_pointcloud2(cloud, Stamp::from_seconds(100.0), stream);
    sample = serialise<sensor_msgs::msg::PointCloud2PubSubType>(msg);
    type_name = sensor_msgs::msg::PointCloud2PubSubType().getName();
    // ... data (sequence<uint8>), is_dense (bool): the last byte.
    last_sequence_length = sample.bytes.size() - 1 - msg.data().size() - 4;
    if (topic.empty()) topic = "rt/" + stream + "/points";
  } else if (type == "patch") {
    Keyframe kf;
    kf.key = {stream, 0};
    kf.stamp = Stamp::from_seconds(100.0);
    kf.covariance = Matrix6d::Identity() * 1e-4;
    kf.voxel_size = 1.0;
    for (int i = 0; i < distributions; ++i) {
      Distribution d;
      d.mean = Eigen::Vector3d(i, 0.5 * i, 1.0);
      d.cov = Eigen::Matrix3d::Identity() * 0.1;
      d.count = 10;
      kf.distributions.push_back(d);
    }
    auto msg = litamin2::dds::to_map_patch(kf, stream + "/odom");
    sample = serialise<litamin2::msg::MapPatchPubSubType>(msg);
    type_name = litamin2::msg::MapPatchPubSubType().getName();
    element_bytes = 40;
    last_sequence_length = sample.bytes.size() - 40 * msg.distributions().size() - 4;
    if (topic.empty()) topic = "rt/litamin2/map_patches";
  } else if (type == "odom") {
    auto msg = litamin2::dds::to_odometry(Eigen::Isometry3d::Identity(),
                                          Matrix6d::Identity() * 1e-4, Stamp::from_seconds(100.0),
                                          stream + "/odom", stream + "/base_link");
    sample = serialise<nav_msgs::msg::OdometryPubSubType>(msg);
    type_name = nav_msgs::msg::OdometryPubSubType().getName();
    if (topic.empty()) topic = "rt/" + stream + "/odom";
  } else {
    std::fprintf(stderr, "raw_cdr_writer: unknown --type %s\n", type.c_str());
    return 2;
  }

  if (malformation == "bad_bool") {
    if (type != "points") {
      std::fprintf(stderr,
                   "raw_cdr_writer: bad_bool needs --type points (the others have no bool)\n");
      return 2;
    }
    sample.bytes.back() = 2;
  } else if (malformation == "truncated") {
    const std::size_t keep = last_sequence_length ? last_sequence_length + 4 + element_bytes * 3 / 2
                                                  : sample.bytes.size() / 2;
    sample.bytes.resize(keep);
  } else if (malformation == "length_beyond") {
    if (last_sequence_length == 0) {
      std::fprintf(stderr, "raw_cdr_writer: length_beyond needs a type with a sequence\n");
      return 2;
    }
    put_u32(sample.bytes, last_sequence_length, 0x7fffffffu);
  } else if (malformation != "valid") {
    std::fprintf(stderr, "raw_cdr_writer: unknown --malformation %s\n", malformation.c_str());
    return 2;
  }

  litamin2::dds::ParticipantPtr participant =
      litamin2::testing::probe_participant(dds_options, "raw_cdr_writer");
  if (!participant) return 1;
  fdds::TypeSupport raw(new RawType(type_name, type == "patch"));
  raw.register_type(participant.get());
  auto* t = participant->create_topic(topic, type_name, fdds::TOPIC_QOS_DEFAULT);
  if (partitions.empty() && type == "patch") partitions.push_back(stream);
  fdds::PublisherQos publisher_qos = fdds::PUBLISHER_QOS_DEFAULT;
  for (const std::string& p : partitions) publisher_qos.partition().push_back(p.c_str());
  auto* publisher = participant->create_publisher(publisher_qos);
  // The QoS of the topic's real writers, so that their readers match.
  fdds::DataWriterQos qos = type == "patch"  ? litamin2::dds::map_patches_writer_qos(count)
                            : type == "odom" ? litamin2::dds::odom_writer_qos()
                                             : litamin2::dds::points_writer_qos();
  fdds::DataWriter* writer = publisher ? publisher->create_datawriter(t, qos) : nullptr;
  if (!writer) {
    std::string in;
    for (const std::string& p : partitions) in += (in.empty() ? " in partition " : ", ") + p;
    std::fprintf(stderr, "raw_cdr_writer: cannot create a writer of %s%s\n", topic.c_str(),
                 in.c_str());
    return 1;
  }
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(timeout_s));
  fdds::PublicationMatchedStatus matched;
  while (std::chrono::steady_clock::now() < deadline) {
    writer->get_publication_matched_status(matched);
    if (matched.current_count > 0) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (matched.current_count == 0) {
    std::fprintf(stderr, "raw_cdr_writer: no reader of %s matched\n", topic.c_str());
    return 1;
  }
  for (int i = 0; i < count; ++i) writer->write(&sample);
  writer->wait_for_acknowledgments(eprosima::fastrtps::Duration_t(10, 0));
  std::printf("raw_cdr_writer: %d %s sample(s) of %zu bytes (%s) written to %s\n", count,
              malformation.c_str(), sample.bytes.size(), type_name.c_str(), topic.c_str());
  return 0;
}

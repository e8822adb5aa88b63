// Test helper of the DDS replay integration test (dds_replay.sh):
//   dds_replay_subscriber make-sequence DIR FRAMES POINTS SEED
//       writes a small KITTI-layout sequence (velodyne/*.bin, times.txt) of random scans;
//   dds_replay_subscriber subscribe DOMAIN TIMEOUT_S READY_FILE ID=DIR [ID=DIR ...]
//       reads rt/<ID>/points on the loopback profile until every stream has received all scans
//       of its DIR (or TIMEOUT_S), then checks each received scan is bit-identical to the one
//       on disk (points, intensities, stamp from times.txt, frame_id = ID), in order.
// Exit 0 when everything matched, 1 otherwise.

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include "litamin2/dds/participant_factory.hpp"
#include "litamin2/dds/pointcloud2_conversion.hpp"
#include "litamin2/dds/qos.hpp"
#include "litamin2/dds/time_conversion.hpp"
#include "litamin2/io/kitti_bin.hpp"
#include "litamin2/io/kitti_sequence.hpp"
#include "litamin2/service/topic_names.hpp"
#include "sensor_msgs/msg/PointCloud2PubSubTypes.h"

namespace fdds = eprosima::fastdds::dds;
using Clock = std::chrono::steady_clock;

namespace {

int make_sequence(const std::string& dir, int frames, int points, unsigned seed) {
  std::filesystem::create_directories(dir + "/velodyne");
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> coord(-60.0f, 60.0f);
  std::uniform_real_distribution<float> intensity(0.0f, 1.0f);
  std::ofstream times(dir + "/times.txt");
  for (int f = 0; f < frames; ++f) {
    litamin2::PointCloud cloud;
    const int n = points + 3 * f;  // different sizes, never a multiple of 3 if points is not
    for (int i = 0; i < n; ++i) {
      cloud.points.emplace_back(coord(rng), coord(rng), coord(rng) * 0.1f);
      cloud.intensities.push_back(intensity(rng));
    }
    char name[64];
    std::snprintf(name, sizeof(name), "/velodyne/%06d.bin", f);
    litamin2::io::write_kitti_bin(dir + name, cloud);
    char stamp[64];
    std::snprintf(stamp, sizeof(stamp), "%.6e\n", 0.103 * f + 1.0 / 3.0);
    times << stamp;
  }
  return times.good() ? 0 : 1;
}

struct StreamCheck {
  std::string id;
  std::unique_ptr<litamin2::io::ScanSequence> sequence;
  fdds::DataReader* reader = nullptr;
  std::vector<sensor_msgs::msg::PointCloud2> received;
};

int subscribe(std::uint32_t domain, double timeout_s, const std::string& ready_file,
              const std::vector<std::string>& specs) {
  litamin2::dds::ParticipantConfig config;
  config.domain_id = domain;
  config.name = "dds_replay_subscriber";
  std::string error;
  auto participant = litamin2::dds::create_participant(config, &error);
  if (!participant) {
    spdlog::error("{}", error);
    return 1;
  }
  fdds::TypeSupport type(new sensor_msgs::msg::PointCloud2PubSubType());
  type.register_type(participant.get());
  auto* subscriber = participant->create_subscriber(fdds::SUBSCRIBER_QOS_DEFAULT);
  std::vector<StreamCheck> streams;
  for (const auto& spec : specs) {
    const auto eq = spec.find('=');
    if (eq == std::string::npos) {
      spdlog::error("expected ID=DIR, got '{}'", spec);
      return 1;
    }
    StreamCheck s;
    s.id = spec.substr(0, eq);
    s.sequence = std::make_unique<litamin2::io::ScanSequence>(spec.substr(eq + 1));
    auto* topic = participant->create_topic(litamin2::service::points_topic(s.id),
                                            type.get_type_name(), fdds::TOPIC_QOS_DEFAULT);
    s.reader = subscriber->create_datareader(
        topic,
        litamin2::dds::points_reader_qos(true, static_cast<std::int32_t>(s.sequence->size() + 10)));
    if (!s.reader) {
      spdlog::error("cannot create a reader for {}", s.id);
      return 1;
    }
    streams.push_back(std::move(s));
  }
  std::ofstream(ready_file) << "ready\n";

  const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                           std::chrono::duration<double>(timeout_s));
  while (Clock::now() < deadline) {
    bool all = true;
    bool any = false;
    for (auto& s : streams) {
      sensor_msgs::msg::PointCloud2 msg;
      fdds::SampleInfo info;
      while (s.reader->take_next_sample(&msg, &info) == ReturnCode_t::RETCODE_OK) {
        if (info.valid_data) {
          s.received.push_back(msg);
          any = true;
        }
      }
      all = all && s.received.size() >= s.sequence->size();
    }
    if (all) break;
    if (!any) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }

  int failures = 0;
  for (auto& s : streams) {
    const std::size_t n = s.sequence->size();
    if (s.received.size() != n) {
      spdlog::error("{}: received {} of {} scans", s.id, s.received.size(), n);
      ++failures;
    }
    for (std::size_t k = 0; k < std::min(n, s.received.size()); ++k) {
      const auto& msg = s.received[k];
      const auto expected = s.sequence->load(k);
      const auto got = litamin2::dds::from_pointcloud2(msg);
      const auto stamp =
          litamin2::dds::to_time(litamin2::Stamp::from_seconds(s.sequence->timestamp(k)));
      std::string problem;
      if (!got.ok()) {
        problem = std::string("invalid PointCloud2: ") + got.message;
      } else if (msg.header().frame_id() != s.id) {
        problem = "frame_id '" + msg.header().frame_id() + "'";
      } else if (msg.header().stamp().sec() != stamp.sec() ||
                 msg.header().stamp().nanosec() != stamp.nanosec()) {
        problem = "stamp differs from times.txt";
      } else if (got.cloud.points != expected.points ||
                 (expected.has_intensities()
                      ? got.cloud.intensities != expected.intensities
                      : std::any_of(got.cloud.intensities.begin(), got.cloud.intensities.end(),
                                    [](float i) { return i != 0.0f; }))) {
        // A scan without intensities is published with intensity 0.

        problem = "points differ (" + std::to_string(got.cloud.size()) + " vs " +
                  std::to_string(expected.size()) + ")";
      }
      if (!problem.empty()) {
        spdlog::error("{}: scan {}: {}", s.id, k, problem);
        ++failures;
      }
    }
    std::printf("%s: %zu/%zu scans received%s\n", s.id.c_str(), s.received.size(), n,
                failures ? "" : ", identical");
  }
  return failures == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  try {
    if (args.size() == 5 && args[0] == "make-sequence") {
      return make_sequence(args[1], std::stoi(args[2]), std::stoi(args[3]),
                           static_cast<unsigned>(std::stoul(args[4])));
    }
    if (args.size() >= 5 && args[0] == "subscribe") {
      return subscribe(static_cast<std::uint32_t>(std::stoul(args[1])), std::stod(args[2]), args[3],
                       std::vector<std::string>(args.begin() + 4, args.end()));
    }
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  std::fprintf(stderr,
               "usage: dds_replay_subscriber make-sequence DIR FRAMES POINTS SEED\n"
               "       dds_replay_subscriber subscribe DOMAIN TIMEOUT_S READY_FILE ID=DIR...\n");
  return 1;
}

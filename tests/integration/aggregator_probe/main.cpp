// aggregator_probe: the patch source and pose reader of the litamin2-aggregator integration
// tests and benchmark.
//  publish: runs the core Tracker offline on a scan sequence and publishes its keyframes as
//    MapPatch messages (the daemon's conversion) for each --stream, optionally only a range of
//    keyframe ids, twice each (--duplicate), in reverse order (--reverse), at a limited rate;
//    or (--synthetic N) patches of N random distributions for --streams-count streams at
//    --rate patches per second per stream for --duration seconds (the ingest benchmark);
//    with --scene each stream instead drives straight at --speed m/s through its own random
//    scene (ground and objects of random heights) and publishes the N distributions within
//    50 m around it, so that places differ as real ones do.
//    The writer is reliable, transient-local, keep-all, and stays up --linger seconds.
//  poses: reads rt/litamin2/keyframe_poses until every --stream has --expect keyframes (exit 0)
//    or --timeout passes (exit 1); prints each stream's count and frame. --exclusive reads with
//    EXCLUSIVE ownership (aggregators in hot standby); --log FILE writes one line per sample
//    received: wall-clock ns, stream, the stream's keyframes (over the latest sample of each of
//    its chunks), the writer's GUID (which aggregator) and the sample's chunk.

#include "litamin2/core/tracker.hpp"
#include "litamin2/dds/map_patch_conversion.hpp"
#include "litamin2/dds/participant_factory.hpp"
#include "litamin2/dds/qos.hpp"
#include "litamin2/dds/stream_partition.hpp"
#include "litamin2/dds/time_conversion.hpp"
#include "litamin2/io/kitti_sequence.hpp"
#include "litamin2/msg/KeyframePosesPubSubTypes.h"
#include "litamin2/msg/MapPatchPubSubTypes.h"
#include "support/probe_participant.hpp"

#include <CLI/CLI.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/DataWriterListener.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <random>
#include <thread>

namespace fdds = eprosima::fastdds::dds;
using namespace litamin2;

namespace {

using Clock = std::chrono::steady_clock;
constexpr std::int64_t kEpochNs = 1'700'000'000'000'000'000;

class MatchListener : public fdds::DataWriterListener {
 public:
  void on_publication_matched(fdds::DataWriter*, const fdds::PublicationMatchedStatus& s) override {
    matched = s.current_count;
  }
  std::atomic<int> matched{0};
};

/// A writer's GUID (its publication handle) in hex: which aggregator a sample came from.
std::string writer_guid(const fdds::InstanceHandle_t& handle) {
  std::string out;
  char byte[3];
  for (int i = 0; i < 16; ++i) {
    std::snprintf(byte, sizeof byte, "%02x", handle.value[i]);
    out += byte;
  }
  return out;
}

class PosesListener : public fdds::DataReaderListener {
 public:
  explicit PosesListener(std::FILE* log) : log_(log) {}
  void on_data_available(fdds::DataReader* reader) override {
    litamin2::msg::KeyframePoses msg;
    fdds::SampleInfo info;
    while (reader->take_next_sample(&msg, &info) == ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) continue;
      std::lock_guard lock(mutex);
      latest[msg.stream_id()][msg.chunk()] = {msg.keyframes().size(), msg.frame_id()};
      if (log_) {
        const auto now = std::chrono::duration_cast<std::chrono::nanoseconds>(
            std::chrono::system_clock::now().time_since_epoch());
        std::fprintf(log_, "%lld %s %zu %s %llu\n", static_cast<long long>(now.count()),
                     msg.stream_id().c_str(), keyframes(msg.stream_id()),
                     writer_guid(info.publication_handle).c_str(),
                     static_cast<unsigned long long>(msg.chunk()));
        std::fflush(log_);
      }
    }
  }
  /// A stream's keyframes: the sum over the latest sample of each of its chunks (call with
  /// the mutex held).
  std::size_t keyframes(const std::string& stream) const {
    const auto it = latest.find(stream);
    if (it == latest.end()) return 0;
    std::size_t n = 0;
    for (const auto& [chunk, entry] : it->second) n += entry.first;
    return n;
  }
  std::mutex mutex;
  /// Per stream, per chunk of its keyframe ids (KeyframePoses.chunk): keyframes and frame.
  std::map<std::string, std::map<std::uint64_t, std::pair<std::size_t, std::string>>> latest;

 private:
  std::FILE* log_;
};

std::vector<Keyframe> track(const std::string& folder, std::size_t frames) {
  io::ScanSequence sequence(folder);
  Tracker tracker{TrackerConfig{}};
  std::vector<Keyframe> out;
  const std::size_t n = frames > 0 ? std::min(frames, sequence.size()) : sequence.size();
  for (std::size_t i = 0; i < n; ++i) {
    const FrameResult r = tracker.process(sequence.load(i));
    if (!r.keyframe) continue;
    Keyframe kf;
    kf.key.id = out.size();
    kf.stamp.nanoseconds = kEpochNs + static_cast<std::int64_t>(sequence.timestamp(i) * 1e9);
    kf.odom_pose = r.pose;
    kf.covariance = r.covariance;
    kf.voxel_size = tracker.map().voxel_size();
    kf.distributions = tracker.last_distributions();
    out.push_back(std::move(kf));
  }
  return out;
}

std::vector<Distribution> synthetic(std::size_t n, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-50.0, 50.0);
  std::vector<Distribution> out(n);
  for (Distribution& d : out) {
    d.mean = Eigen::Vector3d(u(rng), u(rng), u(rng) * 0.05);
    d.cov = Eigen::Vector3d(0.2, 0.1, 0.01).asDiagonal();
    d.count = 20;
  }
  return out;
}

/// A stream's private random world along x in [x0, x1), |y| < 50: per 100 m x 100 m, n / 2
/// ground distributions and n / 20 objects of 10 distributions stacked to a random height.
std::vector<Distribution> scene(double x0, double x1, std::size_t n, std::mt19937& rng) {
  std::uniform_real_distribution<double> y(-50.0, 50.0), x(x0, x1), height(1.0, 12.0);
  std::normal_distribution<double> jitter(0.0, 0.3);
  const double windows = (x1 - x0) / 100.0;
  std::vector<Distribution> out;
  auto add = [&](const Eigen::Vector3d& mean) {
    Distribution d;
    d.mean = mean;
    d.cov = Eigen::Vector3d(0.2, 0.1, 0.01).asDiagonal();
    d.count = 20;
    out.push_back(d);
  };
  for (std::size_t i = 0; i < static_cast<std::size_t>(windows * n / 2); ++i)
    add({x(rng), y(rng), 0.1 * jitter(rng)});
  for (std::size_t i = 0; i < static_cast<std::size_t>(windows * n / 20); ++i) {
    const Eigen::Vector3d base(x(rng), y(rng), 0.0);
    const double h = height(rng);
    for (int k = 0; k < 10; ++k)
      add(base + Eigen::Vector3d(jitter(rng), jitter(rng), h * (k + 1) / 10.0));
  }
  std::sort(out.begin(), out.end(),
            [](const Distribution& a, const Distribution& b) { return a.mean.x() < b.mean.x(); });
  return out;
}

/// The part of `world` (sorted by x) within 50 m of (x, 0) in x and y, in the frame at x.
std::vector<Distribution> scene_patch(const std::vector<Distribution>& world, double x) {
  auto by_x = [](const Distribution& d, double v) { return d.mean.x() < v; };
  auto first = std::lower_bound(world.begin(), world.end(), x - 50.0, by_x);
  auto last = std::lower_bound(first, world.end(), x + 50.0, by_x);
  std::vector<Distribution> out(first, last);
  for (Distribution& d : out) d.mean.x() -= x;
  return out;
}

/// A benchmark keyframe: stamped kEpochNs (the publisher sets the real stamp), covariance 1e-4 I,
/// 1 m voxels.
Keyframe bench_keyframe(KeyframeKey key, const Eigen::Isometry3d& pose,
                        std::vector<Distribution> distributions) {
  Keyframe kf;
  kf.key = std::move(key);
  kf.stamp = Stamp{kEpochNs};
  kf.odom_pose = pose;
  kf.covariance = Matrix6d::Identity() * 1e-4;
  kf.voxel_size = 1.0;
  kf.distributions = std::move(distributions);
  return kf;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"aggregator_probe: map patches in, corrected poses out"};
  app.require_subcommand(1);
  litamin2::testing::ProbeParticipantOptions dds_options;
  dds_options.add_to(app);

  CLI::App* publish = app.add_subcommand("publish", "publish keyframes as map patches");
  std::string sequence;
  std::size_t frames = 0, synthetic_n = 0;
  std::vector<std::string> streams;
  int streams_count = 0;
  std::int64_t from = 0, to = -1;
  bool duplicate = false, reverse = false;
  double rate = 0.0, linger = 0.0, duration = 10.0, wait_reader = 20.0, speed = 10.0;
  bool with_scene = false;
  std::string count_file;
  publish->add_option("--sequence", sequence, "scan folder (litamin2-sim output)");
  publish->add_option("--frames", frames, "scans of the sequence to track (0 = all)");
  publish->add_option("--stream", streams, "stream id (repeatable)");
  publish->add_option("--from", from, "first keyframe id published");
  publish->add_option("--to", to, "last keyframe id published (-1 = last)");
  publish->add_flag("--duplicate", duplicate, "publish every patch twice");
  publish->add_flag("--reverse", reverse, "publish in reverse keyframe order");
  publish->add_option("--rate", rate, "patches per second (per stream with --synthetic; 0 = max)");
  publish->add_option("--linger", linger, "seconds the writer stays up after publishing");
  publish->add_option("--wait-reader", wait_reader, "seconds to wait for a matched reader");
  publish->add_option("--synthetic", synthetic_n, "random patches of N distributions");
  publish->add_option("--streams-count", streams_count, "--synthetic: streams s000, s001, ...");
  publish->add_option("--duration", duration, "--synthetic: seconds of publishing");
  publish->add_flag("--scene", with_scene, "--synthetic: patches of a moving stream's own scene");
  publish->add_option("--speed", speed, "--scene: metres per second");
  publish->add_option("--count-file", count_file, "write the number of keyframes per stream");

  CLI::App* poses = app.add_subcommand("poses", "wait for corrected keyframe poses");
  std::size_t expect = 0;
  double timeout_s = 60.0;
  std::vector<std::string> pose_streams;
  poses->add_option("--stream", pose_streams)->required();
  poses->add_option("--expect", expect, "keyframes expected per stream")->required();
  poses->add_option("--timeout", timeout_s);
  bool exclusive = false;
  std::string sample_log;
  poses->add_flag("--exclusive", exclusive, "EXCLUSIVE ownership (aggregators in hot standby)");
  poses->add_option("--log", sample_log,
                    "one line per sample: wall ns, stream, keyframes, writer, chunk");
  CLI11_PARSE(app, argc, argv);

  litamin2::dds::ParticipantPtr participant =
      litamin2::testing::probe_participant(dds_options, "aggregator_probe");
  if (!participant) return 1;

  if (poses->parsed()) {
    fdds::TypeSupport type(new litamin2::msg::KeyframePosesPubSubType());
    type.register_type(participant.get());
    auto* topic = participant->create_topic("rt/litamin2/keyframe_poses", type.get_type_name(),
                                            fdds::TOPIC_QOS_DEFAULT);
    fdds::DataReaderQos qos = litamin2::dds::map_patches_reader_qos();
    qos.history().kind = fdds::KEEP_LAST_HISTORY_QOS;
    qos.history().depth = 1;
    if (exclusive) qos = litamin2::dds::exclusive_ownership(qos);
    std::FILE* log = sample_log.empty() ? nullptr : std::fopen(sample_log.c_str(), "w");
    if (!sample_log.empty() && !log) {
      std::fprintf(stderr, "probe: cannot write %s\n", sample_log.c_str());
      return 1;
    }
    PosesListener listener(log);
    auto* subscriber = participant->create_subscriber(fdds::SUBSCRIBER_QOS_DEFAULT);
    subscriber->create_datareader(topic, qos, &listener);
    const auto deadline = Clock::now() + std::chrono::duration<double>(timeout_s);
    bool done = false;
    while (!done && Clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      std::lock_guard lock(listener.mutex);
      done = std::all_of(pose_streams.begin(), pose_streams.end(),
                         [&](const std::string& s) { return listener.keyframes(s) >= expect; });
    }
    {
      std::lock_guard lock(listener.mutex);
      // The frame of the chunk with the newest keyframes.
      for (const auto& [s, chunks] : listener.latest)
        std::printf("poses %s: %zu keyframes in %s (%zu chunks)\n", s.c_str(),
                    listener.keyframes(s), chunks.rbegin()->second.second.c_str(), chunks.size());
    }
    participant.reset();
    if (log) std::fclose(log);
    if (!done) std::fprintf(stderr, "probe: timed out waiting for %zu keyframes\n", expect);
    return done ? 0 : 1;
  }

  fdds::TypeSupport type(new litamin2::msg::MapPatchPubSubType());
  type.register_type(participant.get());
  auto* topic = participant->create_topic("rt/litamin2/map_patches", type.get_type_name(),
                                          fdds::TOPIC_QOS_DEFAULT);
  // One writer per stream, in the partition of the stream id, as litamin2d writes them
  // (dds/stream_partition.hpp: the aggregator refuses a patch outside its writer's partition).
  std::vector<std::string> ids = streams;
  if (synthetic_n > 0) {
    ids.clear();
    for (int s = 0; s < streams_count; ++s) {
      char id[16];
      std::snprintf(id, sizeof id, "s%03d", s);
      ids.push_back(id);
    }
  }
  std::map<std::string, fdds::DataWriter*> writers;
  std::vector<std::unique_ptr<MatchListener>> matches;
  for (const std::string& id : ids) {
    if (writers.count(id)) continue;
    auto* publisher = participant->create_publisher(litamin2::dds::stream_publisher_qos(id));
    matches.push_back(std::make_unique<MatchListener>());
    // Holds every patch it sends, as the load tests count them all at the aggregator.
    auto* w = publisher ? publisher->create_datawriter(
                              topic, litamin2::dds::map_patches_writer_qos(100'000),
                              matches.back().get(), fdds::StatusMask::publication_matched())
                        : nullptr;
    if (!w) {
      std::fprintf(stderr, "probe: no writer for stream %s\n", id.c_str());
      return 1;
    }
    writers[id] = w;
  }
  auto matched = [&] {
    int least = std::numeric_limits<int>::max();
    for (const auto& m : matches) least = std::min(least, m->matched.load());
    return matches.empty() ? 0 : least;
  };
  const auto wait_deadline = Clock::now() + std::chrono::duration<double>(wait_reader);
  while (matched() == 0 && Clock::now() < wait_deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));

  std::size_t published = 0;
  if (synthetic_n > 0) {
    // The benchmark: every stream one patch per 1/rate seconds, for `duration` seconds.
    std::mt19937 rng(7);
    std::vector<litamin2::msg::MapPatch> templates;
    std::vector<std::vector<Distribution>> worlds;
    const double period = rate > 0 ? 1.0 / rate : 1.0;
    for (int s = 0; s < streams_count; ++s) {
      char id[16];
      std::snprintf(id, sizeof id, "s%03d", s);
      if (with_scene)
        worlds.push_back(scene(-60.0, speed * (duration + period) + 60.0, synthetic_n, rng));
      templates.push_back(
          litamin2::dds::to_map_patch(bench_keyframe({id, 0}, Eigen::Isometry3d::Identity(),
                                                     with_scene ? scene_patch(worlds.back(), 0.0)
                                                                : synthetic(synthetic_n, rng)),
                                      std::string(id) + "/odom"));
    }
    const auto start = Clock::now();
    for (std::uint64_t k = 0;; ++k) {
      const auto due = start + std::chrono::duration_cast<Clock::duration>(
                                   std::chrono::duration<double>(k * period));
      if (due - start > std::chrono::duration<double>(duration)) break;
      std::this_thread::sleep_until(due);
      for (std::size_t s = 0; s < templates.size(); ++s) {
        litamin2::msg::MapPatch& msg = templates[s];
        if (with_scene) {
          const double x = speed * static_cast<double>(k) * period;
          Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
          pose.translation().x() = x;
          msg = litamin2::dds::to_map_patch(
              bench_keyframe({msg.stream_id(), k}, pose, scene_patch(worlds[s], x)),
              msg.frame_id());
        }
        msg.keyframe_id(k);
        msg.stamp(litamin2::dds::to_time(
            litamin2::Stamp{kEpochNs + static_cast<std::int64_t>(k * period * 1e9)}));
        if (!with_scene) msg.pose().position().x(static_cast<double>(k));
        if (writers.at(msg.stream_id())->write(&msg)) ++published;
      }
    }
  } else {
    std::vector<Keyframe> keyframes = track(sequence, frames);
    if (!count_file.empty()) {
      if (FILE* f = std::fopen(count_file.c_str(), "w")) {
        std::fprintf(f, "%zu\n", keyframes.size());
        std::fclose(f);
      }
    }
    const std::int64_t last = to < 0 ? static_cast<std::int64_t>(keyframes.size()) - 1 : to;
    std::vector<std::pair<std::string, std::size_t>> order;
    for (std::int64_t i = from; i <= last && i < static_cast<std::int64_t>(keyframes.size()); ++i)
      for (const std::string& s : streams) {
        order.emplace_back(s, static_cast<std::size_t>(i));
        if (duplicate) order.emplace_back(s, static_cast<std::size_t>(i));
      }
    if (reverse) std::reverse(order.begin(), order.end());
    const auto start = Clock::now();
    for (std::size_t k = 0; k < order.size(); ++k) {
      if (rate > 0)
        std::this_thread::sleep_until(start + std::chrono::duration_cast<Clock::duration>(
                                                  std::chrono::duration<double>(k / rate)));
      Keyframe kf = keyframes[order[k].second];
      kf.key.stream = order[k].first;
      litamin2::msg::MapPatch msg = litamin2::dds::to_map_patch(kf, kf.key.stream + "/odom");
      if (writers.at(kf.key.stream)->write(&msg)) ++published;
    }
    std::printf("keyframes %zu, published %zu patch(es)\n", keyframes.size(), published);
  }
  std::fflush(stdout);
  // Reliable delivery of everything written before leaving (or lingering).
  for (auto& [id, w] : writers) w->wait_for_acknowledgments(eprosima::fastrtps::Duration_t(30, 0));
  if (linger > 0) std::this_thread::sleep_for(std::chrono::duration<double>(linger));
  std::fprintf(stderr, "probe: published %zu patch(es), %d reader(s) matched\n", published,
               matched());
  participant.reset();
  return 0;
}

// litamin2-replay: publishes KITTI-format scan sequences as ROS 2 PointCloud2 over DDS, several
// streams at once (see --help and replay_options.cpp).

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <memory>
#include <thread>
#include <vector>

#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include "common/cli.hpp"
#include "litamin2/dds/participant_factory.hpp"
#include "litamin2/dds/qos.hpp"
#include "litamin2/dds/serialized_pointcloud2.hpp"
#include "litamin2/io/io_error.hpp"
#include "litamin2/service/topic_names.hpp"
#include "litamin2_zero_copy/msg/PlainScanPubSubTypes.h"
#include "replay/replay_options.hpp"
#include "replay/stream_publisher.hpp"
#include "sensor_msgs/msg/PointCloud2PubSubTypes.h"

namespace fdds = eprosima::fastdds::dds;
using litamin2::replay::Clock;
using litamin2::replay::ReplayOptions;
using litamin2::replay::StreamPublisher;

namespace {

// 2 is a usage error (common/cli.hpp), reported by parse_replay_options.
constexpr int kExitError = 1;
constexpr int kExitIncomplete = 3;
constexpr int kExitNoSubscribers = 4;
constexpr int kExitInterrupted = 130;

std::atomic<bool> g_stop{false};

extern "C" void on_signal(int) {
  g_stop.store(true);
}

std::string mb(std::uint64_t bytes) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.1f MB", static_cast<double>(bytes) / 1e6);
  return buf;
}

}  // namespace

int main(int argc, char** argv) {
  auto logger = spdlog::stderr_color_mt("litamin2-replay");
  spdlog::set_default_logger(logger);
  spdlog::set_pattern("[%H:%M:%S.%e] [%^%l%$] %v");

  ReplayOptions options;
  bool should_exit = false;
  const int parse_status = litamin2::replay::parse_replay_options(argc, argv, options, should_exit);
  if (should_exit) return parse_status;

  // Open every sequence first: input errors are reported before any DDS traffic.
  std::vector<std::unique_ptr<litamin2::io::ScanSequence>> sequences;
  std::vector<std::pair<std::size_t, std::size_t>> ranges;
  for (const auto& spec : options.streams) {
    try {
      sequences.push_back(std::make_unique<litamin2::io::ScanSequence>(spec.folder));
    } catch (const std::exception& e) {
      return litamin2::tools::runtime_error(
          "litamin2-replay",
          fmt::format("stream {}: cannot open sequence '{}': {}", spec.id, spec.folder, e.what()));
    }
    const std::size_t n = sequences.back()->size();
    if (options.first_frame >= n) {
      return litamin2::tools::usage_error(
          "litamin2-replay", fmt::format("stream {}: --frames starts at {} but '{}' has {} scans",
                                         spec.id, options.first_frame, spec.folder, n));
    }
    ranges.emplace_back(options.first_frame, std::min(options.last_frame, n));
  }

  std::string error;
  litamin2::dds::ParticipantPtr participant =
      litamin2::dds::create_participant(options.participant, &error);
  if (!participant) {
    spdlog::error("{}", error);
    return kExitError;
  }
  // --preload publishes each scan's CDR bytes, serialised once before the start (as rosbag2
  // replays serialised messages): a write then costs a copy, not a serialisation.
  // --zero-copy publishes litamin2_zero_copy/PlainScan into loaned samples (data-sharing on this
  // host).
  fdds::TypeSupport type(
      options.zero_copy
          ? static_cast<fdds::TopicDataType*>(new litamin2_zero_copy::msg::PlainScanPubSubType())
      : options.preload
          ? static_cast<fdds::TopicDataType*>(new litamin2::dds::SerializedPointCloud2Type())
          : new sensor_msgs::msg::PointCloud2PubSubType());
  type.register_type(participant.get());
  fdds::Publisher* publisher = participant->create_publisher(fdds::PUBLISHER_QOS_DEFAULT);
  if (!publisher) {
    spdlog::error("cannot create a DDS publisher");
    return kExitError;
  }
  const auto blocking_ms = static_cast<std::int32_t>(std::min(options.timeout_s, 1e6) * 1000.0);
  const fdds::DataWriterQos writer_qos =
      options.zero_copy
          ? litamin2::dds::zero_copy_writer_qos(options.depth, blocking_ms)
          : litamin2::dds::points_writer_qos(options.best_effort, options.depth, blocking_ms);
  std::vector<std::unique_ptr<StreamPublisher>> streams;
  for (std::size_t s = 0; s < options.streams.size(); ++s) {
    const auto& spec = options.streams[s];
    const std::string topic_name = options.zero_copy ? "rt/" + spec.id + "/plain_scan"
                                                     : litamin2::service::points_topic(spec.id);
    fdds::Topic* topic =
        participant->create_topic(topic_name, type.get_type_name(), fdds::TOPIC_QOS_DEFAULT);
    fdds::DataWriter* writer = topic ? publisher->create_datawriter(topic, writer_qos) : nullptr;
    if (!writer) {
      spdlog::error("stream {}: cannot create a DDS writer on {}", spec.id, topic_name);
      return kExitError;
    }
    streams.push_back(std::make_unique<StreamPublisher>(spec.id, *sequences[s], ranges[s].first,
                                                        ranges[s].second, writer));
    spdlog::info("stream {}: {} frames [{}, {}) of {} on {} ({})", spec.id,
                 ranges[s].second - ranges[s].first, ranges[s].first, ranges[s].second, spec.folder,
                 topic_name,
                 options.zero_copy     ? "PlainScan, loaned samples, reliable keep-all"
                 : options.best_effort ? "best-effort"
                                       : "reliable keep-all");
  }
  if (options.zero_copy) {
    const auto preload_start = Clock::now();
    for (const auto& stream : streams) {
      if (!stream->preload_plain()) {
        spdlog::error("stream {}: cannot preload: {}", stream->stream(), stream->error());
        return kExitError;
      }
    }
    spdlog::info("read {} stream(s) for --zero-copy in {:.1f} s", streams.size(),
                 std::chrono::duration<double>(Clock::now() - preload_start).count());
  }

  if (options.preload) {
    const auto preload_start = Clock::now();
    std::size_t frames = 0;
    for (const auto& stream : streams) {
      if (!stream->preload()) {
        spdlog::error("stream {}: cannot preload: {}", stream->stream(), stream->error());
        return kExitError;
      }
      frames += stream->frame_count();
    }
    spdlog::info("preloaded {} scans in {:.1f} s", frames,
                 std::chrono::duration<double>(Clock::now() - preload_start).count());
  }

  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);

  // Wait for readers, bounded.
  const auto wait_deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                                std::chrono::duration<double>(options.timeout_s));
  if (options.wait_subscribers > 0) {
    spdlog::info("waiting up to {} s for {} reader(s) per stream (domain {}, profile {})",
                 options.timeout_s, options.wait_subscribers, options.participant.domain_id,
                 litamin2::service::to_string(options.participant.transport));
    while (!g_stop.load()) {
      bool all = true;
      for (const auto& stream : streams) {
        all = all && stream->matched_readers() >= options.wait_subscribers;
      }
      if (all) break;
      if (Clock::now() >= wait_deadline) {
        for (const auto& stream : streams) {
          spdlog::error("stream {}: {} of {} reader(s) matched on {} within {} s", stream->stream(),
                        stream->matched_readers(), options.wait_subscribers,
                        litamin2::service::points_topic(stream->stream()), options.timeout_s);
        }
        spdlog::error(
            "no subscribers: is the daemon running on domain {} with a compatible "
            "profile? (--wait-subscribers 0 publishes without waiting)",
            options.participant.domain_id);
        return kExitNoSubscribers;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
  if (options.start_delay_s > 0.0) {
    std::this_thread::sleep_for(std::chrono::duration<double>(options.start_delay_s));
  }

  // Publish: one thread per stream, one shared schedule.
  const std::chrono::nanoseconds period =
      options.max_rate ? std::chrono::nanoseconds(0)
                       : std::chrono::nanoseconds(static_cast<std::int64_t>(1e9 / options.rate_hz));
  std::size_t total_frames = 0;
  for (const auto& stream : streams) total_frames += stream->frame_count();
  spdlog::info("publishing {} frames of {} stream(s)", total_frames, streams.size());
  const auto start = Clock::now() + std::chrono::milliseconds(10);
  {
    // The schedule on the system clock, so that a subscriber on this host can compute each
    // scan's delay from its slot (tests/integration/daemon_bench.sh): stream s's frame i is due
    // at start + i * period (+ s * period / streams with --stagger).
    const auto system_start =
        std::chrono::system_clock::now() +
        std::chrono::duration_cast<std::chrono::system_clock::duration>(start - Clock::now());
    spdlog::info("schedule: first slot {:.6f} s since the epoch, period {} ns, stagger {}",
                 std::chrono::duration<double>(system_start.time_since_epoch()).count(),
                 period.count(), options.stagger ? "on" : "off");
  }
  std::vector<std::thread> threads;
  for (std::size_t s = 0; s < streams.size(); ++s) {
    const auto stream_start = options.stagger
                                  ? start + period * static_cast<std::int64_t>(s) /
                                                static_cast<std::int64_t>(streams.size())
                                  : start;
    threads.emplace_back([&stream = streams[s], stream_start, period, &options] {
      stream->run(stream_start, period, g_stop, !options.best_effort, options.timeout_s);
    });
  }
  std::atomic<bool> done{false};
  std::thread progress([&] {
    auto next = Clock::now() + std::chrono::seconds(2);
    while (!done.load()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      if (Clock::now() < next) continue;
      next += std::chrono::seconds(2);
      std::size_t published = 0;
      for (const auto& stream : streams) published += stream->counters().published.load();
      spdlog::info("published {}/{} frames ({:.1f} s)", published, total_frames,
                   std::chrono::duration<double>(Clock::now() - start).count());
    }
  });
  for (auto& t : threads) t.join();
  done.store(true);
  progress.join();
  const double publish_s = std::chrono::duration<double>(Clock::now() - start).count();

  // Reliable writers: wait until every reader has every sample.
  bool acknowledged = true;
  if (!options.best_effort && !g_stop.load()) {
    for (auto& stream : streams) {
      if (!stream->wait_for_acknowledgments(options.timeout_s)) {
        spdlog::error("stream {}: not every reader acknowledged within {} s", stream->stream(),
                      options.timeout_s);
        acknowledged = false;
      }
    }
  }

  // Summary on stdout.
  std::size_t published = 0;
  std::size_t failed = 0;
  std::uint64_t bytes = 0;
  std::uint64_t points = 0;
  bool stream_error = false;
  for (const auto& stream : streams) {
    const auto& c = stream->counters();
    const double rate =
        stream->elapsed_s() > 0 ? static_cast<double>(c.published) / stream->elapsed_s() : 0.0;
    const double write_ms =
        c.published + c.failed > 0
            ? static_cast<double>(c.write_ns) / 1e6 / static_cast<double>(c.published + c.failed)
            : 0.0;
    std::printf(
        "stream %s: %zu/%zu frames published, %zu failed, %zu retried, %.2f M points, %s in "
        "%.2f s: %.2f frames/s, mean write %.2f ms, latest start %.1f ms after its slot, %zu over "
        "5 ms%s\n",
        stream->stream().c_str(), c.published.load(), stream->frame_count(), c.failed.load(),
        c.retried.load(), static_cast<double>(c.points) / 1e6, mb(c.bytes).c_str(),
        stream->elapsed_s(), rate, write_ms, static_cast<double>(c.max_late_ns) / 1e6,
        c.late_over_5ms.load(),
        stream->error().empty() ? "" : (" (stopped: " + stream->error() + ")").c_str());
    published += c.published;
    failed += c.failed;
    bytes += c.bytes;
    points += c.points;
    stream_error = stream_error || !stream->error().empty();
  }
  std::printf(
      "total: %zu streams, %zu/%zu frames, %zu failed, %.2f M points, %s in %.2f s: "
      "%.1f frames/s, %.1f MB/s%s\n",
      streams.size(), published, total_frames, failed, static_cast<double>(points) / 1e6,
      mb(bytes).c_str(), publish_s, publish_s > 0 ? published / publish_s : 0.0,
      publish_s > 0 ? static_cast<double>(bytes) / 1e6 / publish_s : 0.0,
      options.best_effort ? "" : (acknowledged ? ", all acknowledged" : ", NOT all acknowledged"));
  std::fflush(stdout);

  if (g_stop.load()) return kExitInterrupted;
  if (stream_error) return kExitError;
  if (failed > 0 || published != total_frames || !acknowledged) return kExitIncomplete;
  return 0;
}

#include "replay/replay_options.hpp"

#include <spdlog/spdlog.h>

#include <cmath>

#include "common/cli.hpp"
#include "common/frame_range.hpp"
#include "litamin2/service/topic_names.hpp"

namespace litamin2::replay {

namespace {}  // namespace

int parse_replay_options(int argc, char** argv, ReplayOptions& options, bool& should_exit) {
  should_exit = true;
  CLI::App app{
      "litamin2-replay: scan sequences published as PointCloud2 over DDS\n"
      "Publishes KITTI-format scan sequences (a folder with velodyne/*.bin and "
      "times.txt, or a plain folder of .bin/.pcd scans) as ROS 2 sensor_msgs/PointCloud2 on the "
      "DDS topic rt/<stream>/points, one stream per SEQUENCE_DIR, all streams at once. Header "
      "stamps come from times.txt, frame_id is the stream id.\n\n"
      "Delivery: by default each writer is reliable keep-all (history --depth): when a reader is "
      "slower than --rate, write() blocks until it has acknowledged, so no scan is lost (the "
      "rate drops instead). --best-effort uses best-effort keep-last writers (scans may be lost, "
      "the rate is kept). Before publishing, each writer waits for --wait-subscribers matched "
      "readers; after the last frame, reliable writers wait for acknowledgments. Every wait is "
      "bounded by --timeout.\n\n"
      "Exit status: 0 all frames published (and acknowledged when reliable), 1 input or DDS "
      "error, 2 usage error, 3 frames failed or not acknowledged, 4 no subscribers within "
      "--timeout, 130 interrupted.",
      "litamin2-replay"};
  std::vector<std::string> stream_ids;
  std::vector<std::string> folders;
  std::string profile = "loopback";
  std::string frames;
  std::uint32_t domain = 0;
  app.add_option("--stream,-s", stream_ids,
                 "Stream id of each SEQUENCE_DIR, in order (ROS name rules: letters, digits, '_', "
                 "'/' between tokens)")
      ->required()
      ->allow_extra_args(false);  // one id per --stream: folders after it stay positional
  auto* rate =
      app.add_option("--rate", options.rate_hz, "Frames per second per stream (default 10)");
  auto* max = app.add_flag("--max", options.max_rate,
                           "Publish as fast as the writers allow (reliable: as fast as the "
                           "slowest reader acknowledges)");
  rate->excludes(max);
  app.add_flag("--stagger", options.stagger,
               "Spread the streams over one period (stream s of N starts s/N of a period "
               "later), as independent sensors are; default: all streams publish at the same "
               "instants (the worst case for a subscriber)")
      ->excludes(max);
  app.add_flag("--preload", options.preload,
               "Read, convert and serialise (CDR) every scan before publishing the first, then "
               "publish the stored bytes, as a recorder replays serialised messages (memory: ~2 "
               "MB per HDL-64 scan and stream, freed as written), so that the publisher costs "
               "little CPU beside the subscribers; for benchmarks on one machine");
  auto* zero_copy = app.add_flag(
      "--zero-copy", options.zero_copy,
      "Publish the fixed-size litamin2_zero_copy/PlainScan (not a ROS 2 type; at most 131072 "
      "points) on "
      "rt/<stream>/plain_scan instead of PointCloud2 on rt/<stream>/points, for litamin2d's "
      "opt-in streams[].zero_copy_topic on this host: every scan is read before publishing "
      "and copied once into a sample loaned from the writer's data-sharing pool (reliable "
      "keep-all, --depth samples)");
  app.add_option("--domain", domain, "DDS domain id (default 0)")->check(CLI::Range(0, 232));
  app.add_option("--profile", profile,
                 "Transport: loopback (default: 127.0.0.1 and shared memory only), shm, default, "
                 "or FILE.xml[:PROFILE] (Fast DDS XML, participant profile name default "
                 "'litamin2')");
  std::string pki, identity;
  app.add_option("--pki", pki,
                 "DDS-Security: a folder made by scripts/litamin2-pki (with --identity)");
  app.add_option("--identity", identity, "DDS-Security: the identity in --pki to publish as");
  tools::add_frames_option(app, frames, "frames of every sequence");
  app.add_option("--wait-subscribers", options.wait_subscribers,
                 "Matched readers each stream waits for before publishing (default 1, 0 = none)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--start-delay", options.start_delay_s,
                 "Seconds to wait after the readers matched before the first scan, e.g. for "
                 "subscribers of a discovering daemon's odometry to match it (default 0)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--timeout", options.timeout_s,
                 "Bound of each wait: readers, acknowledgments, a blocked write (s, default 30)")
      ->check(CLI::PositiveNumber);
  app.add_flag("--best-effort", options.best_effort,
               "Best-effort keep-last writers (default: reliable keep-all)");
  app.add_option("--depth", options.depth, "Writer history depth (default 10)")
      ->check(CLI::Range(1, 10000));
  zero_copy->excludes("--preload")->excludes("--best-effort");
  app.add_option("SEQUENCE_DIR", folders, "Sequence folders, one per --stream")->required();

  tools::init_cli(app, "litamin2-replay");
  if (const auto status = tools::parse_cli(app, argc, argv)) return *status;

  const auto fail = [&app](const std::string& message) {
    return tools::usage_error(app.get_name(), message);
  };
  if (stream_ids.size() != folders.size()) {
    return fail("got " + std::to_string(stream_ids.size()) + " --stream id(s) for " +
                std::to_string(folders.size()) +
                " SEQUENCE_DIR(s): give one --stream per folder, in the same order");
  }
  for (std::size_t i = 0; i < stream_ids.size(); ++i) {
    if (auto error = service::stream_id_error(stream_ids[i])) {
      return fail("--stream '" + stream_ids[i] + "': " + *error);
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (stream_ids[j] == stream_ids[i])
        return fail("--stream '" + stream_ids[i] + "' given twice");
    }
    options.streams.push_back({stream_ids[i], folders[i]});
  }
  if (!options.max_rate && !(options.rate_hz > 0.0 && std::isfinite(options.rate_hz))) {
    return fail("--rate must be a positive number of frames per second (or use --max)");
  }
  std::string error;
  auto participant = dds::parse_participant_profile(profile, &error);
  if (!participant) return fail("--profile: " + error);
  options.participant = *participant;
  options.participant.domain_id = domain;
  options.participant.name = "litamin2-replay";
  if (pki.empty() != identity.empty()) return fail("--pki and --identity go together");
  if (!pki.empty()) options.participant.security = service::pki_identity(pki, identity);
  const auto range = tools::parse_frame_range(frames, &error);
  if (!range) return fail(error);
  options.first_frame = range->first;
  options.last_frame = range->last;
  should_exit = false;
  return 0;
}

}  // namespace litamin2::replay

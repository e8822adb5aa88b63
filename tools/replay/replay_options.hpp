#pragma once
/// Command line of litamin2-replay.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "litamin2/dds/participant_factory.hpp"

namespace litamin2::replay {

/// One stream: a sequence folder published on rt/<id>/points.
struct StreamSpec {
  std::string id;
  std::string folder;
};

struct ReplayOptions {
  std::vector<StreamSpec> streams;
  /// Frames per second per stream; 0 with `max_rate` = as fast as the writers allow.
  double rate_hz = 10.0;
  bool max_rate = false;
  dds::ParticipantConfig participant;
  /// Frames [first, last) of each sequence (last clamped to the sequence's size).
  std::size_t first_frame = 0;
  std::size_t last_frame = static_cast<std::size_t>(-1);
  /// Readers each writer waits for before publishing (0: publish at once).
  int wait_subscribers = 1;
  /// Bound of every wait (readers, acknowledgments, a blocked write), seconds.
  double timeout_s = 30.0;
  /// Pause after the readers matched and before the first scan, seconds: a daemon that starts
  /// a stream on discovery creates its odometry writer at the same moment as its reader, and
  /// its own subscribers need a moment to match that writer.
  double start_delay_s = 0.0;
  /// Best-effort keep-last writers instead of reliable keep-all ones.
  bool best_effort = false;
  /// Writer history depth (keep-all: samples held until acknowledged).
  int depth = 10;
  /// Read and convert every scan before the first is published, so that reading and
  /// converting do not share the CPU with the subscribers while publishing (benchmarks on one
  /// machine). Costs the scans' size in memory (~2 MB per HDL-64 scan and stream); each is
  /// freed once written.
  bool preload = false;
  /// Publish litamin2_zero_copy/PlainScan on rt/<id>/plain_scan (a stream's opt-in zero-copy input,
  /// streams[].zero_copy_topic; same host only) instead of PointCloud2 on rt/<id>/points: every
  /// scan is read before the first is published and copied once into a sample loaned from the
  /// writer's data-sharing pool. Excludes --preload and --best-effort.
  bool zero_copy = false;
  /// Spread the streams' schedules over one period (stream s starts s/N of a period later),
  /// as independent sensors are, instead of publishing every stream's frame at the same instant.
  bool stagger = false;
};

/// Parses the command line. Returns 0 and fills `options` to run, or the process exit code
/// when it should stop (0 for --help / --version, 2 for a usage error, already reported on
/// stderr as "litamin2-replay: error: ...").
int parse_replay_options(int argc, char** argv, ReplayOptions& options, bool& should_exit);

}  // namespace litamin2::replay

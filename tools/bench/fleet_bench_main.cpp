// litamin2-fleet-bench: the aggregator's mapping thread at fleet scale, in process and at full
// speed. V vehicles drive a shared street grid (fleet_drive.hpp) in a cheap model of the
// simulator's world (fleet_world.hpp), making keyframes of ~500 distributions; a generator
// thread feeds them to the PatchQueue and the aggregator's MappingWorker runs as in the daemon:
// AggregatorCore::ingest (store transaction, place search, verification, local optimisation),
// the map tiles' update, the background full pass (FullPassWorker) and the publication of poses,
// tiles and summary into a counting sink. The DDS ingest bench
// (tests/integration/aggregator_bench.sh) covers the transport. At the end the store is reopened
// in a new process, as the aggregator restarts (fleet_restart.hpp: time to serving, that
// process's peak RSS, the recovered graph's digest), then in this one for the accuracy figures.
// Writes a JSON summary (docs/benchmarks.md).
//
// --max-wall-s, SIGINT and SIGTERM stop the feeding early: the generator makes no more
// keyframes, the mapping thread ingests what is queued and stops as at the normal end, the
// store is reopened (restart) and the JSON holds the keyframes reached, "stopped_early" and
// "target_keyframes". A second SIGINT/SIGTERM after that ends the process at once.

#include "common/cli.hpp"
#include "fleet_drive.hpp"
#include "fleet_restart.hpp"
#include "fleet_world.hpp"
#include "litamin2/aggregator/aggregator_core.hpp"
#include "litamin2/aggregator/aggregator_sink.hpp"
#include "litamin2/aggregator/mapping_worker.hpp"
#include "litamin2/aggregator/patch_queue.hpp"
#include "litamin2/core/stopwatch.hpp"
#include "litamin2/io/trajectory.hpp"
#include "litamin2/service/service_signals.hpp"

#include <nlohmann/json.hpp>

#include <sys/resource.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <thread>

using namespace litamin2;
using namespace litamin2::aggregator;
using namespace litamin2::bench;
using Clock = std::chrono::steady_clock;

namespace {

struct Options {
  int vehicles = 100;
  std::size_t keyframes = 10000;
  double max_wall_s = 0.0;
  std::string store = "fleet-bench.db";
  std::string json;
  std::string trajectories;
  int blocks = 10;
  double spacing = 2.0;
  double yaw_bias_deg = FleetDriveConfig{}.yaw_bias_deg;
  double search_spacing = 10.0;
  double loop_spacing = 0.0;
  int local_hold_loops = mapping::PoseGraphConfig{}.local_hold_loops;
  int local_max_free_keyframes = mapping::PoseGraphConfig{}.local_max_free_keyframes;
  bool local_widen_for_loops = mapping::PoseGraphConfig{}.local_widen_for_loops;
  double verification_budget = mapping::PlaceRecognitionConfig{}.verification_budget_per_keyframe;
  double proximity_max_descriptor_distance =
      mapping::PlaceRecognitionConfig{}.proximity_max_descriptor_distance;
  double proximity_cell_size = mapping::PlaceRecognitionConfig{}.proximity_cell_size;
  int proximity_cell_keyframes = mapping::PlaceRecognitionConfig{}.proximity_cell_keyframes;
  double proximity_partner_gap = mapping::PlaceRecognitionConfig{}.proximity_partner_gap;
  int segment_keyframes = 10;
  bool full_pass_shift_segments = mapping::PoseGraphConfig{}.full_pass_shift_segments;
  int full_pass_max_segments = mapping::PoseGraphConfig{}.full_pass_max_segments;
  int iterative_min_free_poses = mapping::PoseGraphConfig{}.iterative_min_free_poses;
  double full_pass_min_shift = mapping::PoseGraphConfig{}.full_pass_min_shift;
  double full_pass_min_turn_deg = mapping::PoseGraphConfig{}.full_pass_min_turn_deg;
  double yaw_drift_window = mapping::PoseGraphConfig{}.yaw_drift_window;
  double loop_rotation_sigma_deg = mapping::LoopVerificationConfig{}.rotation_sigma_deg;
  double loop_consistency_sigmas = mapping::PoseGraphConfig{}.loop_consistency_sigmas;
  double loop_loss_scale = mapping::PoseGraphConfig{}.loop_loss_scale;
  int tile_segment_keyframes = 10;
  int merge_confirmations = 2;
  std::size_t cache_mb = 512;
  bool segment_spill = true;
  double full_pass_duty = 0.25;
  bool full_pass_on_stop = false;
  int poses_chunk = PublishConfig{}.poses_chunk_keyframes;
  unsigned seed = 1;
  bool keep_store = false;
  std::string reopen_only;
  std::string restart_glibc_tunables = kAggregatorGlibcTunables;
  int store_page_size = store::StoreOptions{}.page_size;
  int restart_readers = store::StoreOptions{}.restart_readers;
  int sqlite_cache_mb = store::StoreOptions{}.sqlite_cache_mb;
};

/// Vehicle v's drive seed: the generator's, and the drift check's that draws the same bias.
unsigned drive_seed(unsigned seed, int v) {
  return seed * 7919u + static_cast<unsigned>(v);
}

std::string stream_name(int v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "vehicle_%03d", v);
  return buf;
}

double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;
}

/// This process image's peak RSS (VmHWM), MB. Unlike getrusage's ru_maxrss, which Linux carries
/// across execve (a child started by posix_spawn would report its parent's peak), VmHWM belongs
/// to the address space the process runs in.
double image_peak_rss_mb() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
  }
  return 0.0;
}

double file_mb(const std::string& path) {
  double total = 0.0;
  for (const char* suffix : {"", "-wal"}) {
    std::error_code ec;
    const auto size = std::filesystem::file_size(path + suffix, ec);
    if (!ec) total += static_cast<double>(size);
  }
  return total / (1024.0 * 1024.0);
}

/// RMS translation error after the best rotation about z and translation of the estimate
/// onto the truth (least squares, 2D Umeyama without scale; z follows the mean): the map's
/// shape error, apart from where and how it is turned as a whole. A diagnostic beside the
/// issue's ATE, which allows no alignment beyond the first vehicle's first pose.
double ate_after_yaw_alignment(const std::vector<Eigen::Vector3d>& estimate,
                               const std::vector<Eigen::Vector3d>& truth) {
  const std::size_t n = estimate.size();
  if (n == 0) return 0.0;
  Eigen::Vector3d mean_e = Eigen::Vector3d::Zero(), mean_t = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    mean_e += estimate[i];
    mean_t += truth[i];
  }
  mean_e /= static_cast<double>(n);
  mean_t /= static_cast<double>(n);
  double dot = 0.0, cross = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d e = estimate[i] - mean_e, t = truth[i] - mean_t;
    dot += e.x() * t.x() + e.y() * t.y();
    cross += e.x() * t.y() - e.y() * t.x();
  }
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(std::atan2(cross, dot), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  double sum_sq = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    sum_sq += (turn * (estimate[i] - mean_e) + mean_t - truth[i]).squaredNorm();
  return std::sqrt(sum_sq / static_cast<double>(n));
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const auto i = static_cast<std::size_t>(
      std::min<double>(v.size() - 1, std::floor(p * (v.size() - 1) + 0.5)));
  return v[i];
}

/// Mapping CPU of the keyframes [from, to), from per-batch samples (end keyframe count, CPU s).
double window_ms(const std::vector<std::pair<std::size_t, double>>& batches, std::size_t from,
                 std::size_t to) {
  double cpu = 0.0;
  std::size_t begin = 0, n = 0;
  for (const auto& [end, c] : batches) {
    if (begin >= from && end <= to) {
      cpu += c;
      n += end - begin;
    }
    begin = end;
  }
  return n ? 1000.0 * cpu / n : 0.0;
}

/// Counts what the mapping thread publishes (the DDS writers' place).
struct CountingSink : AggregatorSink {
  std::size_t pose_messages = 0, pose_entries = 0, summaries = 0, tiles = 0;
  void publish_poses(const StreamPoses& poses) override {
    ++pose_messages;
    pose_entries += poses.keyframes.size();
  }
  void publish_summary(const MapSummary&) override { ++summaries; }
  void publish_tile(const TileOutput&) override { ++tiles; }
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"litamin2-fleet-bench: the aggregator's core fed a synthetic fleet in process"};
  litamin2::tools::init_cli(app, "litamin2-fleet-bench");
  Options o;
  app.add_option("--vehicles", o.vehicles, "vehicles (streams)")->check(CLI::Range(1, 100000));
  app.add_option("--keyframes", o.keyframes, "keyframes in all")->check(CLI::Range(1, 100000000));
  app.add_option("--max-wall-s", o.max_wall_s,
                 "stop feeding after this many seconds of wall time and finish as at the end "
                 "(0: no bound; SIGINT/SIGTERM do the same)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--store", o.store, "the store to create (removed first)");
  app.add_option("--json", o.json, "summary JSON");
  app.add_option("--trajectories", o.trajectories,
                 "folder for <vehicle>.kitti and <vehicle>_gt.kitti (map frame)");
  app.add_option("--blocks", o.blocks, "street grid size, blocks per side")
      ->check(CLI::Range(2, 1000));
  app.add_option("--spacing", o.spacing, "metres between keyframes");
  app.add_option("--yaw-bias-deg", o.yaw_bias_deg,
                 "each vehicle's odometry yaw bias is drawn from +-this, degrees per keyframe")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--search-spacing", o.search_spacing, "place_recognition.search_spacing, metres");
  app.add_option("--loop-spacing", o.loop_spacing, "place_recognition.loop_spacing, metres");
  app.add_option("--local-hold-loops", o.local_hold_loops, "pose_graph.local_hold_loops")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--local-max-free-keyframes", o.local_max_free_keyframes,
                 "pose_graph.local_max_free_keyframes (0 = no bound)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--local-widen-for-loops", o.local_widen_for_loops,
                 "pose_graph.local_widen_for_loops (0 or 1)");
  app.add_option("--verification-budget", o.verification_budget,
                 "place_recognition.verification_budget_per_keyframe")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--proximity-max-descriptor-distance", o.proximity_max_descriptor_distance,
                 "place_recognition.proximity_max_descriptor_distance")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--proximity-cell-size", o.proximity_cell_size,
                 "place_recognition.proximity_cell_size, m")
      ->check(CLI::PositiveNumber);
  app.add_option("--proximity-cell-keyframes", o.proximity_cell_keyframes,
                 "place_recognition.proximity_cell_keyframes (0: every keyframe of a cell)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--proximity-partner-gap", o.proximity_partner_gap,
                 "place_recognition.proximity_partner_gap, metres (0: the nearest keyframe)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--segment-keyframes", o.segment_keyframes, "pose_graph.segment_keyframes");
  app.add_option("--full-pass-shift-segments", o.full_pass_shift_segments,
                 "pose_graph.full_pass_shift_segments (0 or 1)");
  app.add_option("--full-pass-min-shift", o.full_pass_min_shift,
                 "pose_graph.full_pass_min_shift, m")
      ->check(CLI::Range(0.0, 10.0));
  app.add_option("--yaw-drift-window", o.yaw_drift_window,
                 "pose_graph.yaw_drift_window, metres (0: the odometry edges keep the drift)")
      ->check(CLI::Range(0.0, 1e7));
  app.add_option("--loop-rotation-sigma-deg", o.loop_rotation_sigma_deg,
                 "verification.rotation_sigma_deg: the loop edges' rotation standard deviation")
      ->check(CLI::Range(1e-4, 90.0));
  app.add_option("--loop-consistency-sigmas", o.loop_consistency_sigmas,
                 "pose_graph.loop_consistency_sigmas: a new loop the local solve leaves further "
                 "off than this is dropped")
      ->check(CLI::Range(0.5, 1000.0));
  app.add_option("--loop-loss-scale", o.loop_loss_scale,
                 "pose_graph.loop_loss_scale: the Cauchy scale of checked loop edges, sigmas")
      ->check(CLI::Range(0.01, 1000.0));
  app.add_option("--full-pass-min-turn-deg", o.full_pass_min_turn_deg,
                 "pose_graph.full_pass_min_turn_deg")
      ->check(CLI::Range(0.0, 10.0));
  app.add_option("--full-pass-max-segments", o.full_pass_max_segments,
                 "pose_graph.full_pass_max_segments (0: no bound)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--iterative-min-free-poses", o.iterative_min_free_poses,
                 "pose_graph.iterative_min_free_poses (0: always the sparse Cholesky factor)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--tile-segment-keyframes", o.tile_segment_keyframes,
                 "map_tiles.segment_keyframes (0: tiles fused keyframe by keyframe)")
      ->check(CLI::Range(0, 100000));
  app.add_option("--merge-confirmations", o.merge_confirmations,
                 "place_recognition.merge_confirmations (1: two groups join at their first loop)")
      ->check(CLI::Range(1, 100));
  app.add_option("--cache-mb", o.cache_mb, "distribution cache, MB");
  app.add_option("--segment-spill", o.segment_spill,
                 "spill evicted tile segments' moments to a scratch file (0: recompute them)");
  app.add_option("--full-pass-duty", o.full_pass_duty, "full pass's share of a core (0 = none)");
  app.add_option("--full-pass-on-stop", o.full_pass_on_stop,
                 "a last full pass, waited for, when the feeding ends (0 or 1; 0: the one in "
                 "flight is applied and the figures are those of the graph as it runs)");
  app.add_option("--poses-chunk", o.poses_chunk,
                 "publish.poses_chunk_keyframes (0: a stream's poses in one piece)")
      ->check(CLI::Range(0, 10000000));
  app.add_option("--seed", o.seed, "world and fleet seed");
  app.add_flag("--keep-store", o.keep_store, "use an existing store instead of removing it");
  app.add_option("--restart-glibc-tunables", o.restart_glibc_tunables,
                 "GLIBC_TUNABLES of the restart's process (default: the aggregator unit's; empty: "
                 "this process's environment)");
  app.add_option("--store-page-size", o.store_page_size,
                 "bytes of an SQLite page of the store the run creates (store.page_size_kb)");
  app.add_option("--restart-readers", o.restart_readers,
                 "connections reading the graph's rows at the restart (store.restart_readers)");
  app.add_option("--sqlite-cache-mb", o.sqlite_cache_mb,
                 "MiB of SQLite's page cache per connection (store.sqlite_cache_mb)");
  app.add_option("--reopen-only", o.reopen_only,
                 "only open the existing --store as the aggregator does at start and write the "
                 "restart's time, peak RSS and graph digest to this JSON file (the bench runs "
                 "itself so after a run: a restart is a new process)");
  if (const auto status = litamin2::tools::parse_cli(app, argc, argv)) return *status;

  mapping::MapperConfig mapper;
  mapper.place.search_spacing = o.search_spacing;
  mapper.place.loop_spacing = o.loop_spacing;
  mapper.graph.local_hold_loops = o.local_hold_loops;
  mapper.graph.local_max_free_keyframes = o.local_max_free_keyframes;
  mapper.graph.local_widen_for_loops = o.local_widen_for_loops;
  mapper.place.verification_budget_per_keyframe = o.verification_budget;
  mapper.place.proximity_max_descriptor_distance = o.proximity_max_descriptor_distance;
  mapper.place.proximity_cell_size = o.proximity_cell_size;
  mapper.place.proximity_cell_keyframes = o.proximity_cell_keyframes;
  mapper.place.proximity_partner_gap = o.proximity_partner_gap;
  mapper.graph.segment_keyframes = o.segment_keyframes;
  mapper.graph.full_pass_shift_segments = o.full_pass_shift_segments;
  mapper.graph.full_pass_max_segments = o.full_pass_max_segments;
  mapper.graph.iterative_min_free_poses = o.iterative_min_free_poses;
  mapper.graph.full_pass_min_shift = o.full_pass_min_shift;
  mapper.graph.full_pass_min_turn_deg = o.full_pass_min_turn_deg;
  mapper.graph.yaw_drift_window = o.yaw_drift_window;
  mapper.verification.rotation_sigma_deg = o.loop_rotation_sigma_deg;
  mapper.graph.loop_consistency_sigmas = o.loop_consistency_sigmas;
  mapper.graph.loop_loss_scale = o.loop_loss_scale;
  mapper.place.merge_confirmations = o.merge_confirmations;
  mapper.graph.odometry_covariance = mapping::OdometryCovariance::kDistance;
  CoreOptions core_options;
  core_options.distribution_cache_bytes = o.cache_mb << 20;
  core_options.spill_segments = o.segment_spill;
  // The aggregator's configuration (defaults) but for the options above; by default no last
  // synchronous full pass at the end (the one in flight is applied).
  AggregatorConfig config;
  config.mapper = mapper;
  config.full_pass.max_duty = o.full_pass_duty;
  config.full_pass.on_stop = o.full_pass_on_stop;
  config.ingest.max_batch = o.vehicles;
  config.publish.poses_chunk_keyframes = o.poses_chunk;
  config.map_tiles.tiles.segment_keyframes = o.tile_segment_keyframes;
  core_options.tiles = config.map_tiles.tiles;
  core_options.tile_cache_bytes = static_cast<std::size_t>(config.map_tiles.cache_mb) << 20;
  store::StoreOptions store_options;
  store_options.page_size = o.store_page_size;
  store_options.restart_readers = o.restart_readers;
  store_options.sqlite_cache_mb = o.sqlite_cache_mb;

  if (!o.reopen_only.empty()) {
    RestartReport report;
    const auto r0 = Clock::now();
    AggregatorCore reopened(o.store, store::OpenMode::kMustExist, mapper, store_options, {},
                            core_options);
    report.restart_s = std::chrono::duration<double>(Clock::now() - r0).count();
    report.peak_rss_mb = image_peak_rss_mb();
    report.keyframes = reopened.mapper().graph().size();
    report.loops = reopened.mapper().loops().size();
    report.digest = graph_digest(reopened.mapper());
    write_restart_report(o.reopen_only, report);
    return 0;
  }

  // SIGINT/SIGTERM blocked before any thread exists; the main thread collects them while the
  // generator feeds (no async handler).
  std::optional<service::ServiceSignals> signals;
  signals.emplace();
  if (!o.keep_store) {
    for (const char* suffix : {"", "-wal", "-shm"}) std::filesystem::remove(o.store + suffix);
  }
  FleetWorldConfig world_config;
  world_config.blocks = o.blocks;
  world_config.seed = o.seed;
  const FleetWorld world(world_config);
  FleetDriveConfig drive_config;
  drive_config.blocks = o.blocks;
  drive_config.spacing = o.spacing;
  drive_config.yaw_bias_deg = o.yaw_bias_deg;

  std::fprintf(stderr, "fleet-bench: %d vehicles, %zu keyframes, world of %zu voxels, store %s\n",
               o.vehicles, o.keyframes, world.voxels(), o.store.c_str());
  // Ground truth of every keyframe, in vehicle 0's first frame, in the order made (keyframe k
  // of vehicle v at k * vehicles + v), compact (56 B a keyframe): the bench's own memory counts
  // in the peak RSS. Written by the generator only, read after it is joined.
  struct TruthPose {
    Eigen::Quaterniond rotation;
    Eigen::Vector3d translation;
  };
  std::vector<TruthPose> truth_poses;
  truth_poses.reserve(o.keyframes);
  std::map<std::string, std::size_t> vehicle_index;
  for (int v = 0; v < o.vehicles; ++v) vehicle_index[stream_name(v)] = static_cast<std::size_t>(v);
  auto truth = [&](const KeyframeKey& key) {
    const TruthPose& t = truth_poses.at(key.id * static_cast<std::size_t>(o.vehicles) +
                                        vehicle_index.at(key.stream));
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = t.rotation.toRotationMatrix();
    pose.translation() = t.translation;
    return pose;
  };
  PatchQueue queue(static_cast<std::size_t>(4 * o.vehicles));
  double distributions_total = 0.0;  // the generator's; read after it is joined
  std::size_t made = 0;              // the generator's; read after it is joined
  std::atomic<bool> stop_feeding{false}, generator_done{false};
  const auto wall_start = Clock::now();
  std::thread generator([&] {
    std::vector<FleetVehicleDrive> drives;
    std::vector<std::mt19937> rngs;
    for (int v = 0; v < o.vehicles; ++v) {
      drives.emplace_back(drive_config, drive_seed(o.seed, v));
      rngs.emplace_back(o.seed * 104729u + static_cast<unsigned>(v));
    }
    Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
    for (std::uint64_t k = 0; made < o.keyframes && !stop_feeding; ++k) {
      for (int v = 0; v < o.vehicles && made < o.keyframes && !stop_feeding; ++v, ++made) {
        FleetVehicleDrive& d = drives[static_cast<std::size_t>(v)];
        d.next();
        if (k == 0 && v == 0) origin = d.truth().inverse();
        Keyframe kf;
        kf.key = {stream_name(v), k};
        kf.stamp.nanoseconds = static_cast<std::int64_t>(k) * 1000000000 + v * 1000000;
        kf.odom_pose = d.odometry();
        kf.voxel_size = 3.0;
        kf.distributions = world.patch(d.truth(), rngs[static_cast<std::size_t>(v)]);
        distributions_total += static_cast<double>(kf.distributions.size());
        const Eigen::Isometry3d true_pose = origin * d.truth();
        truth_poses.push_back({Eigen::Quaterniond(true_pose.linear()), true_pose.translation()});
        if (!queue.push(std::move(kf))) {
          generator_done = true;
          return;
        }
      }
    }
    queue.close();
    generator_done = true;
  });

  std::size_t keyframes = 0, loops = 0, full_passes = 0;
  std::uint64_t live_digest = 0;  // of the graph the run ended with (fleet_restart.hpp)
  std::size_t live_keyframes = 0;
  std::vector<std::pair<std::size_t, double>> batches;  // (keyframes after, mapping CPU s)
  std::vector<double> loop_latency_ms;
  double background_cpu_s = 0.0;
  CountingSink sink;
  std::size_t tiles = 0, map_pending = 0, diverged = 0, descriptor_loads = 0;
  mapping::MapperStats final_stats;
  mapping::TileMapStats tile_stats;
  std::string stop_reason;  // why the feeding stopped before the target ("" if it did not)
  double feed_wall_s = 0.0;
  {
    AggregatorCore core(o.store, store::OpenMode::kCreateIfMissing, mapper, store_options, {},
                        core_options);
    MappingWorker worker(core, queue, sink, config);
    std::size_t next_report = 10000;
    IngestCpu last_in;
    mapping::MapperCpu last_mc;
    mapping::DistributionCacheStats last_cache;
    mapping::MapperStats last_ms;
    mapping::TileMapStats last_ts;
    std::size_t reported_keyframes = 0;
    double last_poses_cpu = 0.0, last_summary_cpu = 0.0, last_tiles_cpu = 0.0;
    // The local optimisations since the last report: solves, keyframes, loop edges, iterations.
    std::size_t local_solves = 0, local_keyframes = 0, local_loop_edges = 0, local_iterations = 0,
                local_held = 0, local_free = 0, local_bounded = 0, local_bounded_solves = 0,
                local_widened = 0;
    // On the mapping thread after each turn: its CPU, loop latencies and a report per 10k.
    worker.observe([&](const TurnReport& turn) {
      keyframes += turn.added;
      if (turn.optimization.ran) {
        ++local_solves;
        local_keyframes += static_cast<std::size_t>(turn.optimization.keyframes);
        local_loop_edges += static_cast<std::size_t>(turn.optimization.loop_edges);
        local_iterations += static_cast<std::size_t>(turn.optimization.iterations);
        local_held += static_cast<std::size_t>(turn.optimization.held_ends);
        local_free += static_cast<std::size_t>(turn.optimization.free_keyframes);
        local_bounded += static_cast<std::size_t>(turn.optimization.bounded_keyframes);
        if (turn.optimization.bounded_keyframes > 0) ++local_bounded_solves;
        if (turn.optimization.widened) ++local_widened;
      }
      batches.emplace_back(keyframes, turn.cpu_s);
      loop_latency_ms.insert(loop_latency_ms.end(), turn.loop_latency_ms.begin(),
                             turn.loop_latency_ms.end());
      if (keyframes < next_report) return;
      next_report += keyframes < 100000 ? 10000 : 50000;
      std::fprintf(stderr,
                   "%zu keyframes, %zu loops, %.2f ms/keyframe (last 10k), rss %.0f MB, %.0f s\n",
                   keyframes, core.mapper().loops().size(),
                   window_ms(batches, keyframes > 10000 ? keyframes - 10000 : 0, keyframes),
                   peak_rss_mb(), std::chrono::duration<double>(Clock::now() - wall_start).count());
      // Where the mapping thread's time went since the last report, ms per keyframe.
      const IngestCpu in = core.cpu();
      const mapping::MapperCpu mc = core.mapper().cpu();
      const mapping::DistributionCacheStats cs = core.mapper().cache().stats();
      const mapping::MapperStats ms = core.mapper().stats();
      const WorkerStatus ws = worker.status();
      const mapping::TileMapStats ts = core.tiles().stats();
      const double k = 1000.0 / static_cast<double>(keyframes - reported_keyframes);
      std::fprintf(
          stderr,
          "  stages ms/keyframe: store %.2f, regularize %.2f, descriptor search %.2f, "
          "proximity %.2f, verification %.2f, local optimisation %.2f, save graph %.2f, "
          "full pass apply %.2f, tiles fuse %.2f store %.2f, publish poses %.2f summary "
          "%.2f tiles %.2f; cache misses %zu of %zu (loads %.2f); %zu candidates, %zu "
          "verified, %zu local solves refused (ran off); %zu tiles, %zu keyframes to fuse; "
          "tile segments %zu, placements %zu, recomputed %zu, spill reads %zu writes %zu "
          "(%.0f MB file), %.0f MB\n",
          k * (in.store_s - last_in.store_s), k * (in.regularize_s - last_in.regularize_s),
          k * (mc.descriptor_search_s - last_mc.descriptor_search_s),
          k * (mc.proximity_s - last_mc.proximity_s),
          k * (mc.verification_s - last_mc.verification_s),
          k * (in.optimize_s - last_in.optimize_s), k * (in.save_graph_s - last_in.save_graph_s),
          k * (in.full_pass_apply_s - last_in.full_pass_apply_s),
          k * (in.map_fuse_s - last_in.map_fuse_s), k * (in.map_store_s - last_in.map_store_s),
          k * (ws.poses_cpu_s - last_poses_cpu), k * (ws.summary_cpu_s - last_summary_cpu),
          k * (ws.tiles_cpu_s - last_tiles_cpu), cs.misses - last_cache.misses,
          cs.misses - last_cache.misses + cs.hits - last_cache.hits,
          k * (cs.load_s - last_cache.load_s), ms.candidates - last_ms.candidates,
          ms.verified - last_ms.verified, ms.diverged, core.tiles().index().size(),
          core.map_pending(), ts.segments, ts.segment_placements - last_ts.segment_placements,
          ts.segment_recomputes - last_ts.segment_recomputes,
          ts.segment_spill_reads - last_ts.segment_spill_reads,
          ts.segment_spill_writes - last_ts.segment_spill_writes,
          static_cast<double>(ts.segment_spill_bytes) / 1048576.0, ts.segment_bytes / 1048576.0);
      const double solves = static_cast<double>(std::max<std::size_t>(local_solves, 1));
      std::fprintf(
          stderr,
          "  local solves %zu: per solve %.0f keyframes (%.0f free, %.0f held by the "
          "bound in %zu solves, %zu widened), %.0f loop edges, %.1f "
          "iterations, %.1f older ends held; proximity candidates %zu verified "
          "(%zu accepted), %zu skipped by descriptor; %zu descriptor searches; %zu searches "
          "over budget; full passes moved %zu keyframes\n",
          local_solves, static_cast<double>(local_keyframes) / solves,
          static_cast<double>(local_free) / solves, static_cast<double>(local_bounded) / solves,
          local_bounded_solves, local_widened, static_cast<double>(local_loop_edges) / solves,
          static_cast<double>(local_iterations) / solves, static_cast<double>(local_held) / solves,
          ms.proximity_candidates - last_ms.proximity_candidates,
          ms.proximity_verified - last_ms.proximity_verified,
          ms.proximity_skipped - last_ms.proximity_skipped,
          ms.descriptor_searches - last_ms.descriptor_searches,
          ms.searches_over_budget - last_ms.searches_over_budget,
          ms.full_pass_keyframes_moved - last_ms.full_pass_keyframes_moved);
      local_solves = local_keyframes = local_loop_edges = local_iterations = local_held =
          local_free = local_bounded = local_bounded_solves = local_widened = 0;
      last_ts = ts;
      last_ms = ms;
      last_in = in;
      last_mc = mc;
      last_cache = cs;
      last_poses_cpu = ws.poses_cpu_s;
      last_summary_cpu = ws.summary_cpu_s;
      last_tiles_cpu = ws.tiles_cpu_s;
      reported_keyframes = keyframes;
    });
    worker.start();
    // Until the generator is done, the wall-time bound is reached or SIGINT/SIGTERM arrives.
    while (!generator_done) {
      const int signal = signals->wait_for(std::chrono::milliseconds(200));
      if (signal == SIGINT || signal == SIGTERM) {
        stop_reason = signal == SIGINT ? "SIGINT" : "SIGTERM";
        break;
      }
      if (o.max_wall_s > 0.0 &&
          std::chrono::duration<double>(Clock::now() - wall_start).count() >= o.max_wall_s) {
        stop_reason = "max_wall_s";
        break;
      }
    }
    stop_feeding = true;
    generator.join();
    // From here a SIGINT/SIGTERM takes its default action (ends the process).
    signals.reset();
    feed_wall_s = std::chrono::duration<double>(Clock::now() - wall_start).count();
    if (made >= o.keyframes) stop_reason.clear();
    if (!stop_reason.empty()) {
      std::fprintf(stderr,
                   "fleet-bench: stopped feeding (%s) at %zu of %zu keyframes after %.0f s; "
                   "ingesting what is queued\n",
                   stop_reason.c_str(), made, o.keyframes, feed_wall_s);
    }
    // Ingests what is queued, applies the pass in flight, publishes what is pending.
    worker.stop();
    const WorkerStatus ws = worker.status();
    if (!ws.error.empty()) {
      return litamin2::tools::runtime_error(app.get_name(),
                                            "the mapping thread failed: " + ws.error);
    }
    full_passes = ws.full_passes;
    background_cpu_s = ws.full_pass_cpu_s;
    tiles = core.tiles().index().size();
    map_pending = core.map_pending();
    tile_stats = core.tiles().stats();
    loops = core.mapper().loops().size();
    live_digest = graph_digest(core.mapper());
    live_keyframes = core.mapper().graph().size();
    diverged = core.mapper().stats().diverged;
    descriptor_loads = core.mapper().descriptor_loads();
    final_stats = core.mapper().stats();
  }
  const double wall_s = std::chrono::duration<double>(Clock::now() - wall_start).count();
  const double rss_run = peak_rss_mb();
  std::fprintf(stderr, "fleet-bench: mapping stopped at %zu keyframes after %.0f s; reopening\n",
               keyframes, wall_s);

  // Restart: a new process reopens the final store as the aggregator does, to serving; the
  // graph it recovers is the one the run ended with (every pose, frame and loop).
  const std::string report_path = o.store + ".restart.json";
  RestartReport restart;
  try {
    restart = run_restart_child(std::vector<std::string>(argv, argv + argc), report_path,
                                o.restart_glibc_tunables);
  } catch (const std::exception& e) {
    return litamin2::tools::runtime_error(app.get_name(), e.what());
  }
  std::filesystem::remove(report_path);
  const bool restart_identical = restart.digest == live_digest &&
                                 restart.keyframes == live_keyframes && restart.loops == loops;
  std::fprintf(stderr, "fleet-bench: restart %.2f s, peak RSS %.0f MB, graph %s\n",
               restart.restart_s, restart.peak_rss_mb, restart_identical ? "identical" : "DIFFERS");

  // The accuracy figures from the reopened store, in this process.
  AggregatorCore reopened(o.store, store::OpenMode::kMustExist, mapper, store_options, {},
                          core_options);

  // ATE of every keyframe in the map frame (vehicle 0's odometry frame = its first pose).
  const mapping::Mapper& m = reopened.mapper();
  const std::string anchor = m.map_anchor();
  std::set<std::string> merged;
  std::vector<Eigen::Vector3d> estimated_positions, true_positions;
  for (const mapping::KeyframePose& p : m.poses()) {
    if (p.frame != anchor) continue;
    merged.insert(p.key.stream);
    estimated_positions.push_back(p.pose.translation());
    true_positions.push_back(truth(p.key).translation());
  }
  const std::size_t in_map = estimated_positions.size();
  // RMS of the estimated positions, moved by `align`, against the truth.
  auto rms_error = [&](const Eigen::Isometry3d& align) {
    double sum_sq = 0.0;
    for (std::size_t i = 0; i < in_map; ++i)
      sum_sq += (align * estimated_positions[i] - true_positions[i]).squaredNorm();
    return in_map ? std::sqrt(sum_sq / static_cast<double>(in_map)) : 0.0;
  };
  const double ate = rms_error(Eigen::Isometry3d::Identity());
  const double ate_shape = ate_after_yaw_alignment(estimated_positions, true_positions);
  // The keyframe that holds the map frame, vehicle 0's first (its true pose is the identity):
  // its own error shows whether the frame held, and the ATE aligned by it alone is the issue's
  // "no alignment beyond the first vehicle's first pose" whether or not it did.
  double anchor_error_m = 0.0, anchor_error_deg = 0.0, ate_first_pose_aligned = 0.0;
  if (const auto first = m.pose(KeyframeKey{stream_name(0), 0}); first && first->frame == anchor) {
    const Eigen::Isometry3d align = truth(first->key) * first->pose.inverse();
    anchor_error_m = align.translation().norm();
    anchor_error_deg = Eigen::AngleAxisd(align.linear()).angle() * 180.0 / M_PI;
    ate_first_pose_aligned = rms_error(align);
  }
  estimated_positions = {};
  true_positions = {};

  // Each vehicle's odometry yaw drift as the reopened mapper estimates it from its loops,
  // against the bias it was driven with (the drives' constructors draw it from the seed).
  std::vector<double> drift_error, drift_true;  // deg per 100 m, over the vehicles in the map
  for (int v = 0; v < o.vehicles; ++v) {
    if (!merged.count(stream_name(v))) continue;
    const double to_deg_per_100m = 180.0 / M_PI * 100.0;
    const double bias = FleetVehicleDrive(drive_config, drive_seed(o.seed, v)).yaw_bias_per_m();
    drift_true.push_back(std::abs(bias) * to_deg_per_100m);
    drift_error.push_back(std::abs(m.yaw_drift_per_m(stream_name(v)) - bias) * to_deg_per_100m);
  }

  // Loops against the ground truth: a loop is wrong when its relative pose is more than
  // 1 m or 2 degrees from the true one. The loops that joined two groups of streams (in the
  // order the store recovers them, as Mapper::restore joins them) are counted apart.
  std::size_t wrong_loops = 0, merges = 0, wrong_merges = 0;
  double worst_loop_m = 0.0;
  std::vector<double> loop_error_m, loop_error_deg;  // of every loop, against the truth
  // The loops' mean error, signed, in the frame of their newer keyframe: translation (m) and
  // rotation vector (deg). A bias of the verification's registration shows here, not in the
  // percentiles of the error's size.
  Eigen::Vector3d loop_bias_m = Eigen::Vector3d::Zero(), loop_bias_deg = Eigen::Vector3d::Zero();
  {
    std::map<std::string, std::string> parent;
    auto root = [&](std::string s) {
      while (parent.count(s) && parent[s] != s) s = parent[s];
      return s;
    };
    for (const mapping::LoopEdge& e : m.loops()) {
      const Eigen::Isometry3d truth_rel = truth(e.from).inverse() * truth(e.to);
      const Eigen::Isometry3d error = e.relative.inverse() * truth_rel;
      const double t_err = error.translation().norm();
      const double r_err = Eigen::AngleAxisd(error.rotation()).angle() * 180.0 / M_PI;
      const bool wrong = t_err > 1.0 || r_err > 2.0;
      worst_loop_m = std::max(worst_loop_m, t_err);
      loop_error_m.push_back(t_err);
      loop_error_deg.push_back(r_err);
      const Eigen::AngleAxisd rotation_error(error.rotation());
      loop_bias_m += error.translation();
      loop_bias_deg += rotation_error.angle() * 180.0 / M_PI * rotation_error.axis();
      wrong_loops += wrong;
      if (wrong) {
        const Eigen::Vector3d a = truth(e.from).translation(), b = truth(e.to).translation();
        std::fprintf(stderr,
                     "wrong loop %s/%llu -> %s/%llu: error %.2f m %.2f deg, true places "
                     "(%.1f %.1f) and (%.1f %.1f), fitness %.3f rmse %.3f\n",
                     e.from.stream.c_str(), static_cast<unsigned long long>(e.from.id),
                     e.to.stream.c_str(), static_cast<unsigned long long>(e.to.id), t_err, r_err,
                     a.x(), a.y(), b.x(), b.y(), e.fitness, e.rmse);
      }
      const std::string a = root(e.from.stream), b = root(e.to.stream);
      if (a != b) {
        ++merges;
        wrong_merges += wrong;
        parent[a] = a;
        parent[b] = a;
      }
    }
  }

  if (!loop_error_m.empty()) {
    loop_bias_m /= static_cast<double>(loop_error_m.size());
    loop_bias_deg /= static_cast<double>(loop_error_m.size());
  }

  if (!o.trajectories.empty()) {
    std::filesystem::create_directories(o.trajectories);
    std::map<std::string, std::pair<std::vector<Eigen::Isometry3d>, std::vector<Eigen::Isometry3d>>>
        by;
    for (const mapping::KeyframePose& p : m.poses()) {
      if (p.frame != anchor) continue;
      by[p.key.stream].first.push_back(p.pose);
      by[p.key.stream].second.push_back(truth(p.key));
    }
    for (const auto& [stream, poses] : by) {
      io::write_kitti_poses(o.trajectories + "/" + stream + ".kitti", poses.first);
      io::write_kitti_poses(o.trajectories + "/" + stream + "_gt.kitti", poses.second);
    }
  }

  using Json = nlohmann::ordered_json;
  Json windows = {
      {"all", window_ms(batches, 0, keyframes)},
      {"first_10k", window_ms(batches, 0, std::min<std::size_t>(10000, keyframes))},
      {"last_10k", window_ms(batches, keyframes > 10000 ? keyframes - 10000 : 0, keyframes)}};
  for (std::size_t d = 1; d < keyframes; d *= 10) {
    windows[std::to_string(d) + "-" + std::to_string(std::min(10 * d, keyframes))] =
        window_ms(batches, d, std::min(10 * d, keyframes));
  }
  // Every whole 10k window in order: [0, 10k), [10k, 20k), ...
  Json windows_10k = Json::array();
  for (std::size_t from = 0; from + 10000 <= keyframes; from += 10000) {
    windows_10k.push_back(window_ms(batches, from, from + 10000));
  }
  const Json summary = {
      {"vehicles", o.vehicles},
      {"yaw_bias_deg", o.yaw_bias_deg},
      {"local_hold_loops", o.local_hold_loops},
      {"local_max_free_keyframes", o.local_max_free_keyframes},
      {"local_widen_for_loops", o.local_widen_for_loops},
      {"loop_spacing", o.loop_spacing},
      {"verification_budget_per_keyframe", o.verification_budget},
      {"proximity_max_descriptor_distance", o.proximity_max_descriptor_distance},
      {"proximity_cell_size", o.proximity_cell_size},
      {"proximity_cell_keyframes", o.proximity_cell_keyframes},
      {"proximity_partner_gap", o.proximity_partner_gap},
      {"keyframes", keyframes},
      {"target_keyframes", o.keyframes},
      {"stopped_early", !stop_reason.empty()},
      {"stop_reason", stop_reason},
      {"max_wall_s", o.max_wall_s},
      {"distributions_per_keyframe", keyframes ? distributions_total / keyframes : 0},
      {"loops", loops},
      {"full_passes", full_passes},
      {"full_pass_min_shift", o.full_pass_min_shift},
      {"full_pass_min_turn_deg", o.full_pass_min_turn_deg},
      {"yaw_drift_window", o.yaw_drift_window},
      {"loop_rotation_sigma_deg", o.loop_rotation_sigma_deg},
      {"loop_consistency_sigmas", o.loop_consistency_sigmas},
      {"loop_loss_scale", o.loop_loss_scale},
      {"full_pass_keyframes_moved", final_stats.full_pass_keyframes_moved},
      {"mapping_cpu_ms_per_keyframe", windows},
      {"mapping_cpu_ms_per_keyframe_10k_windows", windows_10k},
      {"background_full_pass_cpu_ms_per_keyframe",
       keyframes ? 1000.0 * background_cpu_s / keyframes : 0.0},
      {"loop_latency_ms_p50", percentile(loop_latency_ms, 0.5)},
      {"loop_latency_ms_p99", percentile(loop_latency_ms, 0.99)},
      {"peak_rss_mb", rss_run},
      {"restart_peak_rss_mb", restart.peak_rss_mb},
      {"store_mb", file_mb(o.store)},
      {"restart_s", restart.restart_s},
      {"restart_glibc_tunables", o.restart_glibc_tunables},
      {"store_page_size", o.store_page_size},
      {"restart_readers", o.restart_readers},
      {"sqlite_cache_mb", o.sqlite_cache_mb},
      {"restart_identical", restart_identical},
      {"wrong_loops", wrong_loops},
      {"loops_dropped_inconsistent", final_stats.inconsistent},
      {"worst_loop_error_m", worst_loop_m},
      {"loop_error_m_p50", percentile(loop_error_m, 0.5)},
      {"loop_error_m_p95", percentile(loop_error_m, 0.95)},
      {"loop_error_deg_p50", percentile(loop_error_deg, 0.5)},
      {"loop_error_deg_p95", percentile(loop_error_deg, 0.95)},
      {"loop_error_mean_m", {loop_bias_m.x(), loop_bias_m.y(), loop_bias_m.z()}},
      {"loop_error_mean_rotation_deg", {loop_bias_deg.x(), loop_bias_deg.y(), loop_bias_deg.z()}},
      {"group_merges", merges},
      {"wrong_group_merges", wrong_merges},
      {"diverged_solves", diverged},
      {"candidates_verified", final_stats.candidates},
      {"descriptors_read_back", descriptor_loads},
      {"proximity_candidates_verified", final_stats.proximity_candidates},
      {"proximity_candidates_accepted", final_stats.proximity_verified},
      {"proximity_candidates_skipped", final_stats.proximity_skipped},
      {"proximity_candidates_new_partner", final_stats.proximity_new_partner},
      {"descriptor_searches", final_stats.descriptor_searches},
      {"searches_over_budget", final_stats.searches_over_budget},
      {"ate_m", ate},
      {"ate_first_pose_aligned_m", ate_first_pose_aligned},
      {"anchor_keyframe_error_m", anchor_error_m},
      {"anchor_keyframe_error_deg", anchor_error_deg},
      {"ate_after_yaw_alignment_m", ate_shape},
      {"yaw_drift_estimates", final_stats.yaw_drift_estimates},
      {"yaw_drift_rejected", final_stats.yaw_drift_rejected},
      {"yaw_drift_true_deg_per_100m_p50", percentile(drift_true, 0.5)},
      {"yaw_drift_error_deg_per_100m_p50", percentile(drift_error, 0.5)},
      {"yaw_drift_error_deg_per_100m_max", percentile(drift_error, 1.0)},
      {"keyframes_in_map_frame", in_map},
      {"vehicles_in_map_frame", merged.size()},
      {"tiles", tiles},
      {"keyframes_not_fused_at_stop", map_pending},
      {"tile_segment_keyframes", o.tile_segment_keyframes},
      {"full_pass_shift_segments", o.full_pass_shift_segments},
      {"full_pass_max_segments", o.full_pass_max_segments},
      {"iterative_min_free_poses", o.iterative_min_free_poses},
      {"full_pass_on_stop", o.full_pass_on_stop},
      {"segment_spill", o.segment_spill},
      {"tile_segments", tile_stats.segments},
      {"tile_segment_placements", tile_stats.segment_placements},
      {"tile_segment_recomputes", tile_stats.segment_recomputes},
      {"tile_segment_spill_reads", tile_stats.segment_spill_reads},
      {"tile_segment_spill_writes", tile_stats.segment_spill_writes},
      {"tile_segment_spill_mb", static_cast<double>(tile_stats.segment_spill_bytes) / 1048576.0},
      {"tile_keyframe_fusions", tile_stats.added + tile_stats.subtracted},
      {"published",
       {{"pose_messages", sink.pose_messages},
        {"pose_entries", sink.pose_entries},
        {"summaries", sink.summaries},
        {"tiles", sink.tiles}}},
      {"feed_wall_s", feed_wall_s},
      {"wall_s", wall_s}};
  // NaN/Inf (an empty window) become null; the text is valid JSON either way.
  const std::string text = summary.dump(2) + "\n";
  std::cout << text;
  if (!o.json.empty()) std::ofstream(o.json) << text;
  return 0;
}

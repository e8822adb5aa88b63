// litamin2-fleet-bench: the aggregator's core at fleet scale, in process and at full speed. V
// vehicles drive a shared street grid (fleet_drive.hpp) in a cheap model of the simulator's
// world (fleet_world.hpp), making keyframes of ~500 distributions; a generator thread feeds
// them, one batch per second of the fleet (one keyframe of every vehicle), to the mapping
// loop: AggregatorCore::ingest (store transaction, place search, verification, local
// optimisation) and the background full pass (FullPassWorker), as the aggregator's mapping
// thread runs them. The DDS ingest bench (tests/integration/aggregator_bench.sh) covers the
// transport. Writes a JSON summary (docs/benchmarks.md).

#include "fleet_drive.hpp"
#include "fleet_world.hpp"
#include "litamin2/aggregator/aggregator_core.hpp"
#include "litamin2/aggregator/full_pass_worker.hpp"
#include "litamin2/aggregator/patch_queue.hpp"
#include "litamin2/core/stopwatch.hpp"
#include "litamin2/io/trajectory.hpp"

#include <sys/resource.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
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
  std::string store = "fleet-bench.db";
  std::string json;
  std::string trajectories;
  int blocks = 10;
  double spacing = 2.0;
  double search_spacing = 10.0;
  int segment_keyframes = 10;
  std::size_t cache_mb = 512;
  double full_pass_duty = 0.25;
  unsigned seed = 1;
  bool keep_store = false;
};

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

double file_mb(const std::string& path) {
  double total = 0.0;
  for (const char* suffix : {"", "-wal"}) {
    std::error_code ec;
    const auto size = std::filesystem::file_size(path + suffix, ec);
    if (!ec) total += static_cast<double>(size);
  }
  return total / (1024.0 * 1024.0);
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

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"litamin2-fleet-bench: the aggregator's core fed a synthetic fleet in process"};
  Options o;
  app.add_option("--vehicles", o.vehicles, "vehicles (streams)")->check(CLI::Range(1, 100000));
  app.add_option("--keyframes", o.keyframes, "keyframes in all")->check(CLI::Range(1, 100000000));
  app.add_option("--store", o.store, "the store to create (removed first)");
  app.add_option("--json", o.json, "summary JSON");
  app.add_option("--trajectories", o.trajectories,
                 "folder for <vehicle>.kitti and <vehicle>_gt.kitti (map frame)");
  app.add_option("--blocks", o.blocks, "street grid size, blocks per side")
      ->check(CLI::Range(2, 1000));
  app.add_option("--spacing", o.spacing, "metres between keyframes");
  app.add_option("--search-spacing", o.search_spacing, "place_recognition.search_spacing, metres");
  app.add_option("--segment-keyframes", o.segment_keyframes, "pose_graph.segment_keyframes");
  app.add_option("--cache-mb", o.cache_mb, "distribution cache, MB");
  app.add_option("--full-pass-duty", o.full_pass_duty, "full pass's share of a core (0 = none)");
  app.add_option("--seed", o.seed, "world and fleet seed");
  app.add_flag("--keep-store", o.keep_store, "use an existing store instead of removing it");
  CLI11_PARSE(app, argc, argv);

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

  mapping::MapperConfig mapper;
  mapper.place.search_spacing = o.search_spacing;
  mapper.graph.segment_keyframes = o.segment_keyframes;
  mapper.graph.odometry_covariance = mapping::OdometryCovariance::kDistance;
  CoreOptions core_options;
  core_options.distribution_cache_bytes = o.cache_mb << 20;
  FullPassConfig full_pass;
  full_pass.max_duty = o.full_pass_duty;

  std::fprintf(stderr, "fleet-bench: %d vehicles, %zu keyframes, world of %zu voxels, store %s\n",
               o.vehicles, o.keyframes, world.voxels(), o.store.c_str());
  // Ground truth of every keyframe, in vehicle 0's first frame.
  std::map<KeyframeKey, Eigen::Isometry3d> truth;
  std::mutex truth_mutex;
  PatchQueue queue(static_cast<std::size_t>(4 * o.vehicles));
  std::thread generator([&] {
    std::vector<FleetVehicleDrive> drives;
    std::vector<std::mt19937> rngs;
    for (int v = 0; v < o.vehicles; ++v) {
      drives.emplace_back(drive_config, o.seed * 7919u + static_cast<unsigned>(v));
      rngs.emplace_back(o.seed * 104729u + static_cast<unsigned>(v));
    }
    Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
    std::size_t made = 0;
    for (std::uint64_t k = 0; made < o.keyframes; ++k) {
      for (int v = 0; v < o.vehicles && made < o.keyframes; ++v, ++made) {
        FleetVehicleDrive& d = drives[static_cast<std::size_t>(v)];
        d.next();
        if (k == 0 && v == 0) origin = d.truth().inverse();
        Keyframe kf;
        kf.key = {stream_name(v), k};
        kf.stamp.nanoseconds = static_cast<std::int64_t>(k) * 1000000000 + v * 1000000;
        kf.odom_pose = d.odometry();
        kf.voxel_size = 3.0;
        kf.distributions = world.patch(d.truth(), rngs[static_cast<std::size_t>(v)]);
        {
          std::lock_guard lock(truth_mutex);
          truth[kf.key] = origin * d.truth();
        }
        if (!queue.push(std::move(kf))) return;
      }
    }
    queue.close();
  });

  std::size_t keyframes = 0, loops = 0, full_passes = 0;
  std::vector<mapping::KeyframePose> live_poses;
  std::vector<std::pair<std::size_t, double>> batches;  // (keyframes after, mapping CPU s)
  std::vector<double> loop_latency_ms;
  double background_cpu_s = 0.0, distributions_total = 0.0;
  const auto wall_start = Clock::now();
  {
    AggregatorCore core(o.store, store::OpenMode::kCreateIfMissing, mapper, {}, {}, core_options);
    FullPassWorker worker;
    auto last_end = Clock::now();
    double last_duration = 0.0, copy_s = 0.0;
    std::vector<Keyframe> batch;
    std::size_t next_report = 10000;
    for (;;) {
      batch.clear();
      const std::size_t n = queue.pop_batch(batch, static_cast<std::size_t>(o.vehicles),
                                            std::chrono::milliseconds(200));
      if (n == 0 && queue.closed() && queue.size() == 0) break;
      const double cpu0 = thread_cpu_seconds();
      const auto t0 = Clock::now();
      for (const Keyframe& kf : batch)
        distributions_total += static_cast<double>(kf.distributions.size());
      if (n > 0) {
        const IngestResult r = core.ingest(batch);
        keyframes += r.added;
        if (r.new_loops > 0) {
          const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
          for (std::size_t i = 0; i < r.new_loops; ++i) loop_latency_ms.push_back(ms);
        }
      }
      // The background full pass: take a solved one back, start the next when due.
      // A pass costs the mapping thread its copy and its application (O(N) each) besides the
      // background solve: the duty cycle counts all three, so passes grow rarer as they grow
      // costlier and their share per keyframe stays bounded.
      if (auto solved = worker.take()) {
        const auto a0 = Clock::now();
        core.apply_full_pass(*solved);
        background_cpu_s += solved->cpu_s;
        last_duration = copy_s + solved->milliseconds / 1000.0 +
                        std::chrono::duration<double>(Clock::now() - a0).count();
        last_end = Clock::now();
        ++full_passes;
      }
      if (!worker.busy() &&
          full_pass_due(full_pass, core.mapper().loops_since_full_pass(),
                        std::chrono::duration<double>(Clock::now() - last_end).count(),
                        last_duration)) {
        const auto c0 = Clock::now();
        worker.submit(core.mapper().full_pass_problem());
        copy_s = std::chrono::duration<double>(Clock::now() - c0).count();
      }
      batches.emplace_back(keyframes, thread_cpu_seconds() - cpu0);
      if (keyframes >= next_report) {
        next_report += keyframes < 100000 ? 10000 : 100000;
        std::fprintf(
            stderr, "%zu keyframes, %zu loops, %.2f ms/keyframe (last 10k), rss %.0f MB, %.0f s\n",
            keyframes, core.mapper().loops().size(),
            window_ms(batches, keyframes > 10000 ? keyframes - 10000 : 0, keyframes), peak_rss_mb(),
            std::chrono::duration<double>(Clock::now() - wall_start).count());
      }
    }
    generator.join();
    worker.wait();
    if (auto solved = worker.take()) {
      core.apply_full_pass(*solved);
      background_cpu_s += solved->cpu_s;
      ++full_passes;
    }
    loops = core.mapper().loops().size();
    live_poses = core.mapper().poses();
  }
  const double wall_s = std::chrono::duration<double>(Clock::now() - wall_start).count();
  const double rss_run = peak_rss_mb();

  // Restart: reopen the final store as the aggregator does, to serving.
  const auto r0 = Clock::now();
  AggregatorCore reopened(o.store, store::OpenMode::kMustExist, mapper, {}, {}, core_options);
  const double restart_s = std::chrono::duration<double>(Clock::now() - r0).count();
  // The recovered graph is the one the run ended with: every pose, frame and loop.
  const std::vector<mapping::KeyframePose> recovered = reopened.mapper().poses();
  bool restart_identical =
      recovered.size() == live_poses.size() && reopened.mapper().loops().size() == loops;
  for (std::size_t i = 0; restart_identical && i < recovered.size(); ++i) {
    restart_identical = recovered[i].key == live_poses[i].key &&
                        recovered[i].frame == live_poses[i].frame &&
                        recovered[i].pose.matrix() == live_poses[i].pose.matrix();
  }

  // ATE of every keyframe in the map frame (vehicle 0's odometry frame = its first pose).
  const mapping::Mapper& m = reopened.mapper();
  const std::string anchor = m.map_anchor();
  double sum_sq = 0.0;
  std::size_t in_map = 0;
  std::set<std::string> merged;
  for (const mapping::KeyframePose& p : m.poses()) {
    if (p.frame != anchor) continue;
    sum_sq += (p.pose.translation() - truth.at(p.key).translation()).squaredNorm();
    ++in_map;
    merged.insert(p.key.stream);
  }
  const double ate = in_map ? std::sqrt(sum_sq / in_map) : 0.0;

  if (!o.trajectories.empty()) {
    std::filesystem::create_directories(o.trajectories);
    std::map<std::string, std::pair<std::vector<Eigen::Isometry3d>, std::vector<Eigen::Isometry3d>>>
        by;
    for (const mapping::KeyframePose& p : m.poses()) {
      if (p.frame != anchor) continue;
      by[p.key.stream].first.push_back(p.pose);
      by[p.key.stream].second.push_back(truth.at(p.key));
    }
    for (const auto& [stream, poses] : by) {
      io::write_kitti_poses(o.trajectories + "/" + stream + ".kitti", poses.first);
      io::write_kitti_poses(o.trajectories + "/" + stream + "_gt.kitti", poses.second);
    }
  }

  std::ostringstream j;
  j.setf(std::ios::fixed);
  j.precision(3);
  j << "{\n  \"vehicles\": " << o.vehicles << ",\n  \"keyframes\": " << keyframes
    << ",\n  \"distributions_per_keyframe\": " << (keyframes ? distributions_total / keyframes : 0)
    << ",\n  \"loops\": " << loops << ",\n  \"full_passes\": " << full_passes
    << ",\n  \"mapping_cpu_ms_per_keyframe\": {\n    \"all\": " << window_ms(batches, 0, keyframes)
    << ",\n    \"first_10k\": " << window_ms(batches, 0, std::min<std::size_t>(10000, keyframes))
    << ",\n    \"last_10k\": "
    << window_ms(batches, keyframes > 10000 ? keyframes - 10000 : 0, keyframes);
  for (std::size_t d = 1; d < keyframes; d *= 10) {
    j << ",\n    \"" << d << "-" << std::min(10 * d, keyframes)
      << "\": " << window_ms(batches, d, std::min(10 * d, keyframes));
  }
  j << "\n  },\n  \"background_full_pass_cpu_ms_per_keyframe\": "
    << (keyframes ? 1000.0 * background_cpu_s / keyframes : 0)
    << ",\n  \"loop_latency_ms_p50\": " << percentile(loop_latency_ms, 0.5)
    << ",\n  \"loop_latency_ms_p99\": " << percentile(loop_latency_ms, 0.99)
    << ",\n  \"peak_rss_mb\": " << rss_run
    << ",\n  \"peak_rss_mb_after_restart\": " << peak_rss_mb()
    << ",\n  \"store_mb\": " << file_mb(o.store) << ",\n  \"restart_s\": " << restart_s
    << ",\n  \"restart_identical\": " << (restart_identical ? "true" : "false")
    << ",\n  \"ate_m\": " << ate << ",\n  \"keyframes_in_map_frame\": " << in_map
    << ",\n  \"vehicles_in_map_frame\": " << merged.size() << ",\n  \"wall_s\": " << wall_s
    << "\n}\n";
  std::cout << j.str();
  if (!o.json.empty()) std::ofstream(o.json) << j.str();
  return 0;
}

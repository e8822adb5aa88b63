// litamin2-odometry: LiTAMIN2 odometry over a recorded sequence of scans.

#include "common/cli.hpp"
#include "common/frame_range.hpp"
#include "common/progress.hpp"
#include "litamin2/config/mapper_config_yaml.hpp"
#include "litamin2/config/tracker_config_yaml.hpp"
#include "litamin2/core/config_error.hpp"
#include "litamin2/core/sensor_preset.hpp"
#include "litamin2/core/stopwatch.hpp"
#include "litamin2/core/tracker.hpp"
#include "litamin2/eval/ate.hpp"
#include "litamin2/eval/kitti_metrics.hpp"
#include "litamin2/io/io_error.hpp"
#include "litamin2/io/kitti_calib.hpp"
#include "litamin2/io/kitti_sequence.hpp"
#include "litamin2/io/trajectory.hpp"
#include "litamin2/mapping/offline_slam.hpp"
#include "litamin2/version.hpp"
#include "odometry/frame_log.hpp"
#include "odometry/run_stats.hpp"

#include <tbb/global_control.h>
#include <tbb/task_arena.h>
#include <CLI/CLI.hpp>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <thread>

namespace fs = std::filesystem;
using namespace litamin2;

namespace {

struct Options {
  std::string input;
  std::string output;
  std::string config_file;
  std::string mode;
  double voxel_size = 0.0;
  int threads = 1;
  std::string kitti_calib;
  double vertical_correction_deg = 0.0;
  std::string frames;
  bool quiet = false;
  bool loop_closure = false;
  std::string mapper_config_file;
  bool deskew = false;
  bool skip_bad_frames = false;
};

/// One line per loop: the two keyframes' scan indices (counted from the first scan run),
/// fitness and RMS surface distance.
void write_loops(const std::string& path, const std::vector<mapping::OfflineSlam::Loop>& loops) {
  std::ofstream out(path);
  out << "# from_scan to_scan fitness rmse_m\n";
  for (const auto& loop : loops)
    out << loop.from_frame << ' ' << loop.to_frame << ' ' << loop.fitness << ' ' << loop.rmse
        << '\n';
}

void print_accuracy(const char* label, const std::optional<tools::Accuracy>& acc) {
  if (!acc) return;
  if (acc->segments > 0) {
    std::printf("%sKITTI metric: %.3f %% translation, %.4f deg/100 m rotation (%zu segments)\n",
                label, acc->translation_percent, acc->rotation_deg_per_100m, acc->segments);
  } else {
    std::printf("%sKITTI metric: undefined (trajectory shorter than 100 m)\n", label);
  }
  std::printf("%sATE: %.3f m translation RMSE, %.3f deg rotation RMSE\n", label,
              acc->ate_translation_m, acc->ate_rotation_deg);
}

/// The scans of --frames (all when empty) of a sequence of `size` scans; B beyond the end is
/// clipped.
std::pair<std::size_t, std::size_t> frames_of(const std::string& spec, std::size_t size) {
  std::string error;
  const auto range = tools::parse_frame_range(spec, &error);
  if (!range) throw CLI::ValidationError("--frames", error);
  const auto frames = range->within(size);
  if (!frames)
    throw CLI::ValidationError("--frames", spec + " selects no scan of " + std::to_string(size));
  return *frames;
}

/// Tr from --kitti-calib: a calib file, a folder with calib.txt, or a sequence number that
/// selects a row of the shared per-sequence table.
std::optional<Eigen::Isometry3d> calibration(const Options& options, const io::ScanSequence& seq) {
  if (options.kitti_calib.empty()) return seq.velo_to_cam();
  const std::string& arg = options.kitti_calib;
  if (fs::exists(arg)) {
    std::optional<int> number;
    try {
      number = io::kitti_sequence_number(options.input);
    } catch (const std::invalid_argument&) {
    }
    return io::read_kitti_velo_to_cam(arg, number);
  }
  throw CLI::ValidationError("--kitti-calib", "no such file or folder: " + arg);
}

std::optional<tools::Accuracy> accuracy(const io::ScanSequence& seq,
                                        const std::optional<Eigen::Isometry3d>& tr,
                                        const std::vector<Eigen::Isometry3d>& poses_cam,
                                        std::size_t first) {
  if (!seq.ground_truth_cam() || !tr) return std::nullopt;
  const auto& all = *seq.ground_truth_cam();
  std::vector<Eigen::Isometry3d> gt(all.begin() + first, all.begin() + first + poses_cam.size());
  const Eigen::Isometry3d origin = gt.front().inverse();
  for (auto& pose : gt) pose = origin * pose;
  const eval::KittiMetrics kitti = eval::compute_kitti_metrics(gt, poses_cam);
  const eval::AteResult ate = eval::compute_ate(gt, poses_cam);
  return tools::Accuracy{kitti.translation_percent, kitti.rotation_deg_per_100m, kitti.segments,
                         ate.translation_rmse, ate.rotation_rmse_deg};
}

int run(const Options& options) {
  TrackerConfig config =
      options.config_file.empty() ? TrackerConfig{} : load_tracker_config(options.config_file);
  if (options.mode == "icp") config.registration.mode = CostMode::kIcp;
  if (options.mode == "icp+cov") config.registration.mode = CostMode::kIcpCov;
  if (options.voxel_size > 0.0) {
    config.voxelizer.voxel_size = options.voxel_size;
    config.explicit_keys.insert("voxelizer.voxel_size");  // a sensor preset leaves it
  }
  if (options.deskew) config.deskew.enabled = true;
  validate(config);

  io::KittiBinOptions bin;
  bin.vertical_angle_correction_deg = options.vertical_correction_deg;
  // Deskew needs per-point times: a KITTI sequence folder's scans with times are in its pcd/.
  const bool pcd_scans = config.deskew.enabled &&
                         fs::is_directory(fs::path(options.input) / "pcd") &&
                         fs::is_directory(fs::path(options.input) / "velodyne");
  const io::ScanSequence sequence(options.input, bin, pcd_scans);
  const auto [first, last] = frames_of(options.frames, sequence.size());
  const std::optional<Eigen::Isometry3d> tr = calibration(options, sequence);
  fs::create_directories(options.output);

  const int threads =
      options.threads > 0 ? options.threads : static_cast<int>(std::thread::hardware_concurrency());
  tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism, threads);
  tbb::task_arena arena(threads);

  Tracker tracker(config);
  std::optional<mapping::OfflineSlam> loop_closure;
  if (options.loop_closure) {
    loop_closure.emplace(options.mapper_config_file.empty()
                             ? mapping::MapperConfig{}
                             : mapping::load_mapper_config(options.mapper_config_file));
  }
  tools::RunStats stats;
  tools::FrameLog frame_log((fs::path(options.output) / "frames.csv").string());
  std::vector<Eigen::Isometry3d> poses;
  std::vector<io::TimedPose> timed;
  tools::Progress progress("odometry", last - first);
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t i = first; i < last; ++i) {
    // The scan's stamp: times.txt as litamin2-replay stamps it, so that litamin2d predicts and
    // deskews with the same numbers (0.1 s steps without times.txt).
    const SweepTiming timing{Stamp::from_seconds(sequence.timestamp(i))};
    PointCloud scan;
    FrameResult frame;
    try {
      scan = sequence.load(i);
    } catch (const io::IoError& e) {
      if (!options.skip_bad_frames) throw;
      // A corrupt file in a long run: logged, the pose extrapolated with the last motion.
      std::fprintf(stderr, "litamin2-odometry: skipping frame %zu: %s\n", i, e.what());
      frame = tracker.skip_frame(timing);
      stats.add_skipped(i, sequence.path(i), e.what());
      frame_log.add_skipped(i, sequence.path(i), sequence.timestamp(i));
      if (loop_closure) loop_closure->add(tracker, frame, timing.stamp);
      poses.push_back(frame.pose);
      continue;
    }
    arena.execute([&] { frame = tracker.process(scan, timing); });
    stats.add(frame);
    frame_log.add(i, sequence.path(i), sequence.timestamp(i), frame);
    if (loop_closure) loop_closure->add(tracker, frame, Stamp::from_seconds(sequence.timestamp(i)));
    poses.push_back(frame.pose);
    progress.update(i - first + 1,
                    std::to_string(static_cast<int>(stats.frames_per_second())) + " frames/s");
  }
  progress.finish();
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const fs::path out(options.output);
  std::optional<tools::Accuracy> odometry_acc;
  if (loop_closure) {
    // poses_kitti.txt is the SLAM result; the odometry alone is kept beside it.
    io::write_kitti_poses((out / "poses_odometry_kitti.txt").string(), poses);
    if (tr) {
      const auto odometry_cam = io::velo_to_cam_trajectory(poses, *tr);
      io::write_kitti_poses((out / "poses_odometry_kitti_cam.txt").string(), odometry_cam);
      odometry_acc = accuracy(sequence, tr, odometry_cam, first);
    }
    poses = loop_closure->corrected(poses);
    std::ofstream(out / "mapper_config.yaml")
        << mapping::mapper_config_to_yaml(loop_closure->mapper().config());
    write_loops((out / "loops.txt").string(), loop_closure->loops());
  }
  for (std::size_t i = 0; i < poses.size(); ++i)
    timed.push_back({sequence.timestamp(first + i), poses[i]});
  io::write_kitti_poses((out / "poses_kitti.txt").string(), poses);
  io::write_tum((out / "poses_tum.txt").string(), timed);
  // The config in use (with `sensor: auto`, the recognised sensor's preset applied).
  std::ofstream((out / "config.yaml").string()) << tracker_config_to_yaml(tracker.config());
  std::optional<tools::Accuracy> acc;
  if (tr) {
    const auto poses_cam = io::velo_to_cam_trajectory(poses, *tr);
    io::write_kitti_poses((out / "poses_kitti_cam.txt").string(), poses_cam);
    acc = accuracy(sequence, tr, poses_cam, first);
  }
  const TrackerConfig& used = tracker.config();
  const std::string mode = used.registration.mode == CostMode::kIcp ? "icp" : "icp+cov";
  const std::string sensor = sensor_name(used.sensor);
  std::ofstream((fs::path(options.output) / "stats.json").string())
      << stats.to_json(mode, sensor, used.voxelizer.voxel_size, threads, wall, acc);

  if (!options.quiet) {
    std::printf(
        "%zu frames, %s, sensor %s, %.1f m voxels, %d thread(s): %.0f frames/s (per frame p50 "
        "%.2f ms, p99 %.2f ms), %zu keyframes, %zu registration failures\n",
        stats.frames(), mode.c_str(), sensor.c_str(), used.voxelizer.voxel_size, threads,
        stats.frames_per_second(), stats.percentile_ms(50), stats.percentile_ms(99),
        stats.keyframes(), stats.failures());
    if (config.deskew.enabled)
      std::printf("deskew: %zu of %zu frames corrected (the others had no per-point times)\n",
                  stats.deskewed(), stats.frames());
    if (stats.skipped() > 0)
      std::printf("%zu corrupt frame(s) skipped (stats.json lists them)\n", stats.skipped());
    if (loop_closure) {
      const mapping::MapperStats ms = loop_closure->mapper().stats();
      const mapping::MapperCpu cpu = loop_closure->mapper().cpu();
      std::printf(
          "loop closure: %zu keyframes, %zu candidates, %zu loops verified, %zu rejected, "
          "%zu optimisations, %.1f s in mapping (CPU: verification %.1f s, optimisation %.1f "
          "s), odometry yaw drift %.3f deg/100 m (%zu estimates)\n",
          ms.keyframes, ms.candidates, ms.verified, ms.rejected, ms.optimizations,
          loop_closure->milliseconds() / 1000.0, cpu.verification_s, cpu.optimize_s,
          loop_closure->mapper().yaw_drift_per_m(mapping::OfflineSlam::kStream) * 18000.0 / M_PI,
          ms.yaw_drift_estimates);
      print_accuracy("odometry only:     ", odometry_acc);
      print_accuracy("with loop closure: ", acc);
    } else {
      print_accuracy("", acc);
    }
    std::printf("wrote %s/{poses_kitti.txt,poses_tum.txt,config.yaml,stats.json,frames.csv%s}\n",
                options.output.c_str(), tr ? ",poses_kitti_cam.txt" : "");
  }
  return stats.failures() > 0 ? 3 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "litamin2-odometry: LiTAMIN2 LiDAR odometry over a recorded sequence\n"
      "INPUT is a KITTI odometry sequence folder (velodyne/*.bin, optional calib.txt, times.txt,\n"
      "poses.txt) or a folder of .bin/.pcd scans taken in name order. Writes, into --output:\n"
      "poses_kitti.txt (sensor poses in the frame of the first scan, 3x4 row-major), "
      "poses_tum.txt,\n"
      "config.yaml (the full config used), stats.json (speed, memory, accuracy if ground truth\n"
      "is known), frames.csv (one row per scan: registered or not, inlier share, recovery,\n"
      "global search, map reset, re-grids, self-hits, time, position) and, with KITTI\n"
      "calibration, poses_kitti_cam.txt (camera-0 convention).\n"
      "With --deskew, each scan's points are corrected for the motion within its sweep before\n"
      "registration, from their per-point times (PCD input with a time field; a KITTI folder's\n"
      "pcd/ scans, as litamin2-sim --sweep-motion writes them, are then read instead of\n"
      "velodyne/). Each scan is predicted with the last motion scaled to the time since the\n"
      "last scan (times.txt's stamps, which must increase; 0.1 s steps without it).\n"
      "With --skip-bad-frames a scan that cannot be read is logged and skipped, its\n"
      "pose extrapolated with the previous motion, and the run goes on.\n"
      "Exit status: 0 ok, 1 bad input (a corrupt scan without --skip-bad-frames), 2 usage error\n"
      "(an option, --frames beyond the sequence, an invalid config file), 3 some frames could not\n"
      "be registered."};
  tools::init_cli(app, "litamin2-odometry");
  Options options;
  app.add_option("INPUT", options.input, "Sequence folder")->required();
  app.add_option("-o,--output", options.output, "Output folder (created)")->required();
  app.add_option("-c,--config", options.config_file,
                 "Tracker config YAML (see config/tracker.yaml)");
  app.add_option("--mode", options.mode, "Cost: icp or icp+cov (overrides the config)")
      ->check(CLI::IsMember({"icp", "icp+cov"}));
  app.add_option("--voxel-size", options.voxel_size, "Voxel edge in metres (overrides the config)")
      ->check(CLI::Range(0.05, 50.0));
  app.add_option("-j,--threads", options.threads, "Threads; 0 = all cores")
      ->check(CLI::Range(0, 1024));
  app.add_option("--kitti-calib", options.kitti_calib,
                 "KITTI calib.txt, a sequence folder, or the per-sequence Tr table (the row is "
                 "chosen by INPUT's sequence number)");
  app.add_option(
      "--vertical-correction", options.vertical_correction_deg,
      "Rotate KITTI HDL-64 points up by this many degrees (KISS-ICP uses 0.205); off by default");
  tools::add_frames_option(app, options.frames, "scans");
  app.add_flag("-q,--quiet", options.quiet, "Print nothing on success");
  app.add_flag("--loop-closure", options.loop_closure,
               "Offline SLAM: close loops with the aggregator's mapping back end; poses_kitti.txt "
               "is then corrected and poses_odometry_kitti.txt holds the odometry alone");
  app.add_flag("--deskew", options.deskew,
               "Correct each scan for the motion within its sweep from its per-point times "
               "(sets deskew.enabled; config/tracker.yaml's deskew section has the rest)");
  app.add_flag("--skip-bad-frames", options.skip_bad_frames,
               "Log a scan that cannot be read (truncated, corrupt) and go on: its pose keeps the "
               "previous motion; stats.json lists the skipped files");
  app.add_option("--mapper-config", options.mapper_config_file,
                 "Mapping back-end config YAML (see config/mapper.yaml); with --loop-closure");
  if (const auto status = tools::parse_cli(app, argc, argv)) return *status;
  try {
    return run(options);
  } catch (const CLI::Error& e) {  // an option that does not fit the input (--frames)
    return tools::usage_error(app.get_name(), e.what());
  } catch (const ConfigError& e) {
    return tools::usage_error(app.get_name(), std::string("invalid configuration: ") + e.what());
  } catch (const std::exception& e) {
    return tools::runtime_error(app.get_name(), e.what());
  }
}

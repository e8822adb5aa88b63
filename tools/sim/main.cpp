// litamin2-sim: ray-casts synthetic LiDAR sequences along real KITTI (or built-in) trajectories
// and writes them in the KITTI odometry layout.

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <tbb/global_control.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/frame_range.hpp"
#include "litamin2/io/io_error.hpp"
#include "litamin2/io/kitti_bin.hpp"
#include "litamin2/io/kitti_calib.hpp"
#include "litamin2/io/trajectory.hpp"
#include "litamin2/sim/builtin_trajectory.hpp"
#include "litamin2/sim/fleet.hpp"
#include "litamin2/sim/random.hpp"
#include "litamin2/sim/raycaster.hpp"
#include "litamin2/sim/scan_statistics.hpp"
#include "litamin2/sim/sequence_writer.hpp"
#include "litamin2/sim/trajectory_window.hpp"
#include "litamin2/sim/world.hpp"

namespace sim = litamin2::sim;
namespace io = litamin2::io;

namespace {

/// The frames of --frames (all when empty) of a trajectory of n poses; the range must lie within
/// it.
std::pair<std::size_t, std::size_t> frames_of(const std::string& spec, std::size_t n) {
  std::string error;
  const auto range = litamin2::tools::parse_frame_range(spec, &error);
  if (!range) throw std::invalid_argument(error);
  if (range->last != std::numeric_limits<std::size_t>::max() && range->last > n) {
    throw std::invalid_argument("--frames " + spec + " exceeds the trajectory's " +
                                std::to_string(n) + " frames");
  }
  const auto frames = range->within(n);
  if (!frames) throw std::invalid_argument("--frames " + spec + " is empty");
  return *frames;
}

/// Sequence number from a file name like ".../05.txt", if it is one.
std::optional<int> sequence_from_filename(const std::string& path) {
  const std::string stem = std::filesystem::path(path).stem().string();
  if (stem.empty() || stem.size() > 3) return std::nullopt;
  for (char c : stem) {
    if (c < '0' || c > '9') return std::nullopt;
  }
  return std::stoi(stem);
}

struct StatsAccumulator {
  std::size_t n = 0;
  double points = 0, v1 = 0, v2 = 0, v3 = 0, v3m5 = 0, v5 = 0, r50 = 0, r90 = 0, rmax = 0;
  void add(const sim::ScanStatistics& s) {
    ++n;
    points += s.points;
    v1 += s.voxels_1m;
    v2 += s.voxels_2m;
    v3 += s.voxels_3m;
    v3m5 += s.voxels_3m_min5;
    v5 += s.voxels_5m;
    r50 += s.range_median;
    r90 += s.range_p90;
    rmax += s.range_max;
  }
};

}  // namespace

int main(int argc, char** argv) {
  auto logger = spdlog::stderr_color_mt("litamin2-sim");
  spdlog::set_default_logger(logger);
  spdlog::set_pattern("[%H:%M:%S.%e] [%^%l%$] %v");

  CLI::App app{
      "Ray-casts synthetic LiDAR scans along a trajectory (KITTI ground truth or built-in) in a "
      "procedural world and writes KITTI odometry folders (velodyne/*.bin, poses.txt, calib.txt, "
      "times.txt)."};
  std::string trajectory_path, builtin, calib_path, sequence_name, frames_spec,
      sensor = "hdl64", output, compare_real;
  std::uint64_t seed = 1;
  int fleet = 0, threads = 0;
  double noise = -1.0, dropout = -1.0, lane_offset = 3.0, density = 1.0;
  auto* traj_opt = app.add_option("--trajectory", trajectory_path,
                                  "KITTI camera-0 pose file (e.g. .../poses/00.txt)")
                       ->check(CLI::ExistingFile);
  app.add_option("--builtin", builtin,
                 "Built-in trajectory instead of --trajectory: loop | highway")
      ->check(CLI::IsMember(sim::builtin_trajectory_names()))
      ->excludes(traj_opt);
  app.add_option("--calib", calib_path,
                 "Calibration: a KITTI calib.txt, a sequence folder, or the per-sequence Tr table "
                 "(then --sequence or a pose file named NN.txt selects the row). Default: Tr of "
                 "KITTI 00-02")
      ->check(CLI::ExistingPath);
  app.add_option("--sequence", sequence_name, "KITTI sequence number for a Tr table, e.g. 00");
  app.add_option("--frames", frames_spec,
                 "Frame range A:B of the trajectory (B exclusive; A: or :B allowed). Default: all");
  app.add_option("--sensor", sensor, "Sensor model")
      ->check(CLI::IsMember(sim::LidarModel::preset_names()));
  app.add_option("--seed", seed, "Seed of the world and the scan noise (default 1)");
  app.add_option("--fleet", fleet,
                 "Simulate N vehicles on the same streets into DIR/vehicle_00 .. (0 = single run "
                 "into DIR)")
      ->check(CLI::Range(0, 64));
  app.add_option("--noise", noise, "Range noise sigma in metres (default: the sensor's, 0.02)")
      ->check(CLI::Range(0.0, 5.0));
  app.add_option("--dropout", dropout, "Random dropout probability (default: the sensor's, 0.01)")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--lane-offset", lane_offset, "Lateral offset of reverse fleet vehicles, m");
  app.add_option("--density", density, "Object density multiplier (0 = ground only)")
      ->check(CLI::Range(0.0, 10.0));
  app.add_option("--threads", threads, "Worker threads (0 = all cores)")
      ->check(CLI::Range(0, 1024));
  app.add_option("--compare-real", compare_real,
                 "Real scan (.bin, xyz or xyzi) whose voxel/range statistics are printed next to "
                 "the mean of the simulated scans")
      ->check(CLI::ExistingFile);
  app.add_option("--output,-o", output, "Output folder")->required();
  CLI11_PARSE(app, argc, argv);

  try {
    std::unique_ptr<tbb::global_control> control;
    if (threads > 0) {
      control = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                      static_cast<std::size_t>(threads));
    }
    if (trajectory_path.empty() && builtin.empty()) builtin = "loop";

    // Calibration.
    Eigen::Isometry3d tr = sim::kitti_default_velo_to_cam();
    std::optional<int> seq;
    if (!sequence_name.empty()) seq = io::kitti_sequence_number(sequence_name);
    if (!seq && !trajectory_path.empty()) seq = sequence_from_filename(trajectory_path);
    if (!calib_path.empty()) {
      tr = sim::orthonormalized(io::read_kitti_velo_to_cam(calib_path, seq));
      spdlog::info("calibration from {}", calib_path);
    } else {
      spdlog::info("no --calib: using Tr of KITTI sequences 00-02");
    }

    // Sensor (velodyne) trajectory in the velodyne frame of frame 0.
    std::vector<Eigen::Isometry3d> velo;
    if (!trajectory_path.empty()) {
      velo = io::cam_to_velo_trajectory(io::read_kitti_poses(trajectory_path), tr);
      spdlog::info("trajectory {}: {} poses", trajectory_path, velo.size());
    } else {
      velo = sim::builtin_trajectory(builtin);
      spdlog::info("built-in trajectory '{}': {} poses", builtin, velo.size());
    }
    const auto [first, last] = frames_of(frames_spec, velo.size());
    // World frame: the velodyne frame of the first simulated frame (z up).
    const Eigen::Isometry3d to_world = velo[first].inverse();
    for (auto& T : velo) T = to_world * T;

    sim::FleetOptions fleet_opt;
    fleet_opt.vehicles = std::max(1, fleet);
    fleet_opt.lane_offset = lane_offset;
    const auto vehicles = sim::plan_fleet(velo, first, last - first, fleet_opt);

    auto model_opt = sim::LidarModel::from_name(sensor);
    sim::LidarModel model = *model_opt;
    if (noise >= 0) model.range_noise_sigma = noise;
    if (dropout >= 0) model.dropout = dropout;

    const auto t_world = std::chrono::steady_clock::now();
    // The world covers the base trajectory around all vehicles' windows (plus 150 m), then the
    // vehicles' own paths (reverse lanes).
    std::size_t lo = first, hi = last;
    for (const auto& v : vehicles) {
      for (std::size_t f : v.source_frames) {
        lo = std::min(lo, f);
        hi = std::max(hi, f + 1);
      }
    }
    std::vector<std::vector<Eigen::Isometry3d>> paths{sim::trajectory_window(velo, lo, hi, 150.0)};
    for (const auto& v : vehicles) paths.push_back(v.sensor_poses);
    sim::WorldOptions wopt;
    wopt.density = density;
    wopt.sensor_height = model.mount_height;
    const sim::World world(paths, seed, wopt);
    spdlog::info("world: {} objects in {} tiles, built in {:.2f} s", world.objects().size(),
                 world.tile_count(),
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t_world).count());

    if (fleet > 0) {
      // Where each vehicle starts in the shared world frame (velodyne convention, KITTI 3x4 row
      // layout), so map-merging tests know the true relative placement of the vehicles.
      std::filesystem::create_directories(output);
      const std::string fleet_path = (std::filesystem::path(output) / "fleet.txt").string();
      FILE* f = std::fopen(fleet_path.c_str(), "w");
      if (!f) throw io::IoError(fleet_path, "cannot open for writing");
      std::fprintf(
          f,
          "# vehicle  start pose of velodyne in the shared world frame (3x4 row-major)  # plan\n");
      for (std::size_t k = 0; k < vehicles.size(); ++k) {
        const Eigen::Matrix<double, 3, 4> m =
            vehicles[k].sensor_poses.front().matrix().topRows<3>();
        std::fprintf(f, "vehicle_%02zu", k);
        for (int r = 0; r < 3; ++r) {
          for (int c = 0; c < 4; ++c) std::fprintf(f, " %.9e", m(r, c));
        }
        std::fprintf(f, "  # %s\n", vehicles[k].description.c_str());
      }
      std::fclose(f);
    }
    StatsAccumulator acc;
    double raycast_s = 0;
    std::size_t frames_total = 0, points_total = 0;
    for (std::size_t k = 0; k < vehicles.size(); ++k) {
      char sub[32];
      std::snprintf(sub, sizeof(sub), "vehicle_%02zu", k);
      const std::string dir = fleet > 0 ? (std::filesystem::path(output) / sub).string() : output;
      if (fleet > 0) spdlog::info("{}: {}", sub, vehicles[k].description);
      sim::Raycaster raycaster(world);
      sim::SequenceWriteOptions wo;
      wo.model = model;
      wo.seed = sim::hash_combine(seed, 1000 + k);
      wo.velo_to_cam = tr;
      auto last_report = std::chrono::steady_clock::now();
      wo.progress = [&](std::size_t done, std::size_t total) {
        const auto now = std::chrono::steady_clock::now();
        if (done == total || std::chrono::duration<double>(now - last_report).count() > 5.0) {
          spdlog::info("{}: frame {}/{}", dir, done, total);
          last_report = now;
        }
      };
      if (!compare_real.empty()) {
        wo.on_scan = [&](std::size_t, const litamin2::PointCloud& c) {
          acc.add(sim::compute_scan_statistics(c));
        };
      }
      const auto r = sim::write_sequence(dir, raycaster, vehicles[k].sensor_poses, wo);
      raycast_s += r.raycast_seconds;
      frames_total += r.frames;
      points_total += r.points;
    }
    spdlog::info("done: {} frames, {:.0f} points/frame, ray casting {:.1f} ms/frame ({} threads)",
                 frames_total, static_cast<double>(points_total) / frames_total,
                 1000.0 * raycast_s / frames_total,
                 tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));

    if (!compare_real.empty()) {
      io::KittiBinOptions bo;
      const auto real = sim::compute_scan_statistics(io::read_kitti_bin(compare_real, bo));
      const double n = static_cast<double>(acc.n);
      std::printf("%-22s %12s %14s\n", "statistic", "real", "simulated(mean)");
      std::printf("%-22s %12zu %14.0f\n", "points", real.points, acc.points / n);
      std::printf("%-22s %12zu %14.0f\n", "1 m voxels", real.voxels_1m, acc.v1 / n);
      std::printf("%-22s %12zu %14.0f\n", "2 m voxels", real.voxels_2m, acc.v2 / n);
      std::printf("%-22s %12zu %14.0f\n", "3 m voxels", real.voxels_3m, acc.v3 / n);
      std::printf("%-22s %12zu %14.0f\n", "3 m voxels >= 5 pts", real.voxels_3m_min5, acc.v3m5 / n);
      std::printf("%-22s %12zu %14.0f\n", "5 m voxels", real.voxels_5m, acc.v5 / n);
      std::printf("%-22s %12.1f %14.1f\n", "range median [m]", real.range_median, acc.r50 / n);
      std::printf("%-22s %12.1f %14.1f\n", "range p90 [m]", real.range_p90, acc.r90 / n);
      std::printf("%-22s %12.1f %14.1f\n", "range max [m]", real.range_max, acc.rmax / n);
    }
    return 0;
  } catch (const io::IoError& e) {
    spdlog::error("{}", e.what());
    return 2;
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
}

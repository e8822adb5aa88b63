// litamin2-sim: ray-casts synthetic LiDAR sequences along real KITTI (or built-in) trajectories
// and writes them in the KITTI odometry layout.

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/cli.hpp"
#include "common/frame_range.hpp"
#include "litamin2/io/io_error.hpp"
#include "litamin2/io/kitti_bin.hpp"
#include "litamin2/io/kitti_calib.hpp"
#include "litamin2/io/kitti_sequence.hpp"
#include "litamin2/io/pcd.hpp"
#include "litamin2/io/trajectory.hpp"
#include "litamin2/sim/builtin_trajectory.hpp"
#include "litamin2/sim/drivable_height.hpp"
#include "litamin2/sim/fleet.hpp"
#include "litamin2/sim/frame_selection.hpp"
#include "litamin2/sim/ground_clearance.hpp"
#include "litamin2/sim/random.hpp"
#include "litamin2/sim/raycaster.hpp"
#include "litamin2/sim/realism.hpp"
#include "litamin2/sim/scan_statistics.hpp"
#include "litamin2/sim/sequence_writer.hpp"
#include "litamin2/sim/traffic.hpp"
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

/// Statistics of real scans: one .bin or .pcd file, or every scan of a folder (a KITTI
/// sequence folder or a folder of .bin/.pcd files), averaged; rings from the given elevations.
sim::ScanStatisticsMean real_statistics(const std::string& path,
                                        const std::vector<double>& elevations_deg) {
  sim::ScanStatisticsMean mean;
  if (std::filesystem::is_directory(path)) {
    const io::ScanSequence seq(path);
    for (std::size_t i = 0; i < seq.size(); ++i) {
      mean.add(sim::compute_scan_statistics(seq.load(i), elevations_deg));
    }
  } else {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    const litamin2::PointCloud cloud =
        ext == ".pcd" ? io::read_pcd(path) : io::read_kitti_bin(path, io::KittiBinOptions{});
    mean.add(sim::compute_scan_statistics(cloud, elevations_deg));
  }
  return mean;
}

/// Parses "A,B[,...]" into `count` numbers; throws std::invalid_argument naming the option.
std::vector<double> parse_numbers(const std::string& text, std::size_t count, const char* option) {
  std::vector<double> out;
  std::size_t pos = 0;
  while (out.size() < count) {
    const std::size_t comma = text.find(',', pos);
    const std::string item = text.substr(pos, comma == std::string::npos ? comma : comma - pos);
    std::size_t used = 0;
    double v = 0.0;
    try {
      v = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (item.empty() || used != item.size() || !std::isfinite(v)) break;
    out.push_back(v);
    if (comma == std::string::npos) break;
    pos = comma + 1;
  }
  if (out.size() != count ||
      std::count(text.begin(), text.end(), ',') + 1 != static_cast<std::ptrdiff_t>(count)) {
    throw std::invalid_argument(std::string(option) + " expects " + std::to_string(count) +
                                " comma-separated numbers, got '" + text + "'");
  }
  return out;
}

std::array<double, 3> parse_triple(const std::string& text, const char* option) {
  const auto v = parse_numbers(text, 3, option);
  if (v[0] < 0 || v[1] < 0 || v[2] < 0 || v[0] + v[1] + v[2] <= 0) {
    throw std::invalid_argument(std::string(option) + " needs shares >= 0 with a positive sum");
  }
  return {v[0], v[1], v[2]};
}

/// The second sensor's pose in the first sensor's frame (the vehicle's base frame of a stream
/// of several sensors) from "x,y,z,roll,pitch,yaw" (metres, degrees; R = Rz(yaw) Ry(pitch)
/// Rx(roll), as litamin2d.yaml's {xyz, rpy_deg}).
Eigen::Isometry3d parse_extrinsic(const std::string& text, const char* option) {
  const auto v = parse_numbers(text, 6, option);
  constexpr double kDeg = M_PI / 180.0;
  Eigen::Isometry3d e = Eigen::Isometry3d::Identity();
  e.linear() = (Eigen::AngleAxisd(v[5] * kDeg, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(v[4] * kDeg, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(v[3] * kDeg, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  e.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
  if (e.translation().norm() > 100.0)
    throw std::invalid_argument(std::string(option) + ": the sensor is more than 100 m away");
  return e;
}

/// DIR/extrinsic.txt: the second sensor's pose in the first sensor's frame, as the 16 numbers
/// of litamin2d.yaml's `extrinsic:` (4x4, row-major) and as xyz / rpy_deg.
void write_extrinsic(const std::string& dir, const Eigen::Isometry3d& e, const std::string& text) {
  const std::string path = (std::filesystem::path(dir) / "extrinsic.txt").string();
  FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw io::IoError(path, "cannot open for writing");
  std::fprintf(f,
               "# pose of this sensor in the first sensor's frame (sensor -> base), 4x4 "
               "row-major; --second-extrinsic %s (x,y,z m, roll,pitch,yaw deg)\n",
               text.c_str());
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) std::fprintf(f, "%.17g%s", e(r, c), r == 3 && c == 3 ? "\n" : " ");
  std::fclose(f);
}

}  // namespace

int main(int argc, char** argv) {
  auto logger = spdlog::stderr_color_mt("litamin2-sim");
  spdlog::set_default_logger(logger);
  spdlog::set_pattern("[%H:%M:%S.%e] [%^%l%$] %v");

  CLI::App app{
      "litamin2-sim: LiDAR simulator writing KITTI odometry sequences\n"
      "Ray-casts synthetic LiDAR scans along a trajectory (KITTI ground truth or built-in) in a "
      "procedural world and writes KITTI odometry folders (velodyne/*.bin, poses.txt, calib.txt, "
      "times.txt).\n"
      "Exit status: 0 written, 1 unreadable input or failed write, 2 usage error."};
  litamin2::tools::init_cli(app, "litamin2-sim");
  std::string trajectory_path, builtin, calib_path, sequence_name, frames_spec,
      sensor = "hdl64", output, compare_real;
  std::uint64_t seed = 1;
  double max_grade = 0.15;
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
  litamin2::tools::add_frames_option(app, frames_spec, "trajectory's frames (default: all)");
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
                 "Real scan (.bin xyz/xyzi or .pcd) or folder of scans whose statistics (mean) are "
                 "printed next to the mean of the simulated scans")
      ->check(CLI::ExistingPath);
  // Realism: a preset and single overrides (docs/simulator.md, "Harder sequences").
  std::string realism = "none", self_hits, mount_tilt, sweep_direction, districts;
  bool sweep_motion_on = false, sweep_motion_off = false, lead_on = false, lead_off = false;
  std::optional<double> sweep_start, drop_frames, oncoming, pedestrians, ground_bumps, grass_height,
      foliage_depth, vegetation;
  std::optional<std::size_t> max_gap;
  std::optional<double> drop_bursts;
  std::string burst_length;
  app.add_option("--realism", realism,
                 "Preset of what real drives add: none (default: the simulator as it was) | "
                 "street (all of the options below, as on a real VLP-16 drive)")
      ->check(CLI::IsMember(sim::realism_names()));
  auto* motion_on = app.add_flag(
      "--sweep-motion", sweep_motion_on,
      "Cast each firing from its own pose within the 100 ms sweep (each point in the sensor "
      "frame of its firing, not deskewed, as drivers publish them; ground truth at the sweep "
      "start) and write DIR/pcd/*.pcd with a per-point time t (s from the sweep start) and ring");
  app.add_flag("--no-sweep-motion", sweep_motion_off, "One pose per sweep (overrides --realism)")
      ->excludes(motion_on);
  app.add_option("--sweep-start", sweep_start,
                 "Azimuth of the first firing, degrees (0 forward, 90 left; Velodyne: 180)")
      ->check(CLI::Range(-360.0, 360.0));
  app.add_option("--sweep-direction", sweep_direction,
                 "Rotation seen from above: ccw (the simulator's default) | cw (Velodyne, Ouster)")
      ->check(CLI::IsMember({"cw", "ccw"}));
  app.add_option(
         "--self-hits", self_hits,
         "Ego vehicle parts that return points: none | roof-rack (the real drive's: 1-1.8 m "
         "behind the sensor)")
      ->check(CLI::IsMember(sim::EgoBody::preset_names()));
  app.add_option("--max-grade", max_grade,
                 "Where the ground check finds the sensor off its mount height (a trajectory that "
                 "climbs where it hardly moves, e.g. KITTI 08's start), the trajectory's heights "
                 "are limited to this grade (rise over run, plus 1 cm a frame) and the world is "
                 "laid again (default 0.15; 0: keep the heights and only warn)")
      ->check(CLI::Range(0.0, 10.0));
  app.add_option("--mount-tilt", mount_tilt,
                 "Sensor mount rotation ROLL,PITCH in degrees (e.g. 1,0; a negative roll as "
                 "--mount-tilt=-1,0.5)");
  app.add_option("--drop-frames", drop_frames,
                 "Probability that a frame is dropped (irregular spacing between files)")
      ->check(CLI::Range(0.0, 0.95));
  app.add_option("--max-gap", max_gap, "Longest run of dropped frames (default 3)")
      ->check(CLI::Range(1, 100));
  app.add_option("--drop-bursts", drop_bursts,
                 "Probability that a burst of dropped frames starts at a frame (breaks of many "
                 "frames, as in the real VLP-16 drive; independent of --drop-frames)")
      ->check(CLI::Range(0.0, 0.5));
  app.add_option("--burst-length", burst_length,
                 "Frames dropped by one burst, MIN:MAX (default 5:15)");
  auto* lead = app.add_flag("--lead-vehicle", lead_on,
                            "A car ahead in the ego lane with a slowly varying gap");
  app.add_flag("--no-lead-vehicle", lead_off, "No lead car (overrides --realism)")->excludes(lead);
  app.add_option("--oncoming", oncoming, "Oncoming cars per km")->check(CLI::Range(0.0, 200.0));
  app.add_option("--pedestrians", pedestrians, "Pedestrians on the sidewalks per km")
      ->check(CLI::Range(0.0, 200.0));
  app.add_option("--districts", districts,
                 "Shares URBAN,SUBURBAN,GREEN of the stretches that are not open highway "
                 "(default 0.55,0.3,0.15)");
  app.add_option("--vegetation", vegetation,
                 "Multiplier of the probability of trees, bushes and hedges (default 1)")
      ->check(CLI::Range(0.0, 10.0));
  app.add_option("--ground-bumps", ground_bumps,
                 "Amplitude of short (2-5 m) ground bumps on the road, m (twice that off it)")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--grass-height", grass_height,
                 "Grass blade height, m: returns come from near the blade tops")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--foliage-depth", foliage_depth,
                 "Mean depth a beam travels into foliage before returning, m")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--output,-o", output, "Output folder")->required();
  // A second LiDAR on the same vehicle (docs/simulator.md, "Two sensors").
  std::string second_sensor, second_extrinsic, second_output;
  auto* second = app.add_option("--second-sensor", second_sensor,
                                "Also simulate a second LiDAR of this model on the same vehicle, "
                                "its scans in its own frame, into --second-output")
                     ->check(CLI::IsMember(sim::LidarModel::preset_names()));
  app.add_option("--second-extrinsic", second_extrinsic,
                 "The second sensor's pose in the first's frame: X,Y,Z,ROLL,PITCH,YAW (m, deg; "
                 "default 0,0,0,0,0,0); written to SECOND_OUTPUT/extrinsic.txt")
      ->needs(second);
  app.add_option("--second-output", second_output,
                 "Output folder of the second sensor (same frames, times and drops as the first)")
      ->needs(second);
  if (const auto status = litamin2::tools::parse_cli(app, argc, argv)) return *status;

  try {
    std::unique_ptr<tbb::global_control> control;
    if (threads > 0) {
      control = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                      static_cast<std::size_t>(threads));
    }
    if (trajectory_path.empty() && builtin.empty()) builtin = "loop";
    Eigen::Isometry3d second_in_first = Eigen::Isometry3d::Identity();
    if (!second_sensor.empty()) {
      if (second_output.empty())
        throw std::invalid_argument("--second-sensor needs --second-output");
      if (fleet > 0) throw std::invalid_argument("--second-sensor: not with --fleet");
      if (!second_extrinsic.empty())
        second_in_first = parse_extrinsic(second_extrinsic, "--second-extrinsic");
    }

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
    auto vehicles = sim::plan_fleet(velo, first, last - first, fleet_opt);

    // Sensor, rig, world, traffic and frame drops: the realism preset, then single overrides.
    sim::RealismSettings real;
    real.model = *sim::LidarModel::from_name(sensor);
    real.world.density = density;
    sim::apply_realism(realism, real);
    sim::LidarModel& model = real.model;
    sim::SensorRig& rig = real.rig;
    if (noise >= 0) model.range_noise_sigma = noise;
    if (dropout >= 0) model.dropout = dropout;
    if (sweep_motion_on || sweep_motion_off) rig.sweep.motion = sweep_motion_on;
    if (sweep_start) rig.sweep.start_azimuth_deg = *sweep_start;
    if (!sweep_direction.empty()) rig.sweep.clockwise = sweep_direction == "cw";
    if (!self_hits.empty()) rig.body = *sim::EgoBody::from_name(self_hits);
    if (!mount_tilt.empty()) {
      const auto tilt = parse_numbers(mount_tilt, 2, "--mount-tilt");
      rig.mount.roll_deg = tilt[0];
      rig.mount.pitch_deg = tilt[1];
    }
    if (drop_frames) real.drops.probability = *drop_frames;
    if (max_gap) real.drops.max_gap = *max_gap;
    if (drop_bursts) real.drops.burst_probability = *drop_bursts;
    if (!burst_length.empty()) {
      const std::size_t colon = burst_length.find(':');
      std::size_t lo = 0, hi = 0;
      bool ok = colon != std::string::npos;
      try {
        std::size_t used_lo = 0, used_hi = 0;
        if (ok) {
          lo = std::stoul(burst_length.substr(0, colon), &used_lo);
          hi = std::stoul(burst_length.substr(colon + 1), &used_hi);
          ok = used_lo == colon && used_hi == burst_length.size() - colon - 1 && hi <= 1000;
        }
      } catch (const std::exception&) {
        ok = false;
      }
      if (!ok) throw std::invalid_argument("--burst-length must be MIN:MAX, got " + burst_length);
      real.drops.burst_min = lo;
      real.drops.burst_max = hi;
    }
    if (lead_on || lead_off) real.traffic.lead_vehicle = lead_on;
    if (oncoming) real.traffic.oncoming_per_km = *oncoming;
    if (pedestrians) real.traffic.pedestrians_per_km = *pedestrians;
    if (!districts.empty()) real.world.district_weights = parse_triple(districts, "--districts");
    if (vegetation) real.world.vegetation_density = *vegetation;
    if (ground_bumps) real.world.ground_bump_amplitude = *ground_bumps;
    if (grass_height) real.world.grass_height = *grass_height;
    if (foliage_depth) real.world.foliage_penetration = *foliage_depth;
    model.validate();
    rig.validate();
    if (!second_sensor.empty() && (rig.mount.roll_deg != 0.0 || rig.mount.pitch_deg != 0.0))
      throw std::invalid_argument(
          "--second-sensor: not with a mount tilt (the first sensor's frame is the base)");
    real.traffic.validate();
    real.drops.validate();
    spdlog::info(
        "realism {}: sweep motion {}, start {} deg {}, self-hits {} boxes, mount roll {} pitch {} "
        "deg, range noise {} m, bumps {} m, grass {} m, foliage {} m, lead car {}, "
        "oncoming {}/km, pedestrians {}/km, frame drops {} (max gap {}), bursts {} ({}:{} frames)",
        realism, rig.sweep.motion, rig.sweep.start_azimuth_deg, rig.sweep.clockwise ? "cw" : "ccw",
        rig.body.boxes.size(), rig.mount.roll_deg, rig.mount.pitch_deg, model.range_noise_sigma,
        real.world.ground_bump_amplitude, real.world.grass_height, real.world.foliage_penetration,
        real.traffic.lead_vehicle, real.traffic.oncoming_per_km, real.traffic.pedestrians_per_km,
        real.drops.probability, real.drops.max_gap, real.drops.burst_probability,
        real.drops.burst_min, real.drops.burst_max);

    sim::WorldOptions wopt = real.world;
    wopt.sensor_height = model.mount_height;
    // The world covers the base trajectory around all vehicles' windows (plus 150 m), then the
    // vehicles' own paths (reverse lanes).
    const auto lay_world = [&]() {
      const auto t_world = std::chrono::steady_clock::now();
      std::size_t lo = first, hi = last;
      for (const auto& v : vehicles) {
        for (std::size_t f : v.source_frames) {
          lo = std::min(lo, f);
          hi = std::max(hi, f + 1);
        }
      }
      std::vector<std::vector<Eigen::Isometry3d>> paths{
          sim::trajectory_window(velo, lo, hi, 150.0)};
      for (const auto& v : vehicles) paths.push_back(v.sensor_poses);
      auto laid = std::make_unique<const sim::World>(paths, seed, wopt);
      spdlog::info(
          "world: {} objects in {} tiles, built in {:.2f} s", laid->objects().size(),
          laid->tile_count(),
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t_world).count());
      return laid;
    };
    // Whether every vehicle's sensor rides at its mount height over the ground laid under it.
    const auto check_clearance = [&](const sim::World& laid, bool warn) {
      bool all_clear = true;
      for (std::size_t k = 0; k < vehicles.size(); ++k) {
        const auto& v = vehicles[k];
        const sim::GroundClearance c =
            sim::check_ground_clearance(laid, v.sensor_poses, model.mount_height, 0.5);
        if (c.poses_off == 0) continue;
        all_clear = false;
        if (!warn) continue;
        spdlog::warn(
            "{}the sensor is up to {:.1f} m off its mount height above the simulated ground at "
            "{} of {} frames (source frames {}-{}): the trajectory climbs or falls where it "
            "hardly moves, and the road laid under it cuts through the scans there (a ground no "
            "vehicle sees; e.g. KITTI 08's first 60 frames)",
            fleet > 0 ? fmt::format("vehicle_{:02}: ", k) : std::string(), c.worst_m, c.poses_off,
            v.sensor_poses.size(), v.source_frames[c.first_off], v.source_frames[c.last_off]);
      }
      return all_clear;
    };
    std::unique_ptr<const sim::World> laid_world = lay_world();
    if (!check_clearance(*laid_world, max_grade <= 0.0)) {
      // A ground truth no road can lie under: its heights limited to a drivable grade, the
      // vehicles planned and the world laid again; poses.txt holds the repaired trajectory.
      constexpr double kStepSlackM = 0.01;
      const std::size_t changed = sim::limit_grade(velo, max_grade, kStepSlackM);
      spdlog::warn(
          "the trajectory climbs or falls where it hardly moves (the sensor left its mount "
          "height above the ground): {} of {} poses' heights limited to a {:.0f} % grade plus "
          "{:.2f} m a frame (--max-grade); the ground truth written is the repaired trajectory",
          changed, velo.size(), 100.0 * max_grade, kStepSlackM);
      vehicles = sim::plan_fleet(velo, first, last - first, fleet_opt);
      laid_world = lay_world();
      check_clearance(*laid_world, true);
    }
    const sim::World& world = *laid_world;

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
    // Moving actors along vehicle 0's drive (other fleet vehicles see the same actors on their
    // own clocks).
    std::unique_ptr<sim::Traffic> traffic;
    if (real.traffic.any()) {
      traffic = std::make_unique<sim::Traffic>(vehicles[0].sensor_poses, 0.1, world,
                                               sim::hash_combine(seed, 77), real.traffic);
      spdlog::info("traffic: {} actors", traffic->size());
    }
    sim::ScanStatisticsMean simulated;
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
      wo.rig = rig;
      wo.traffic = traffic.get();
      wo.write_pcd = rig.sweep.motion;
      if (real.drops.probability > 0 || real.drops.burst_probability > 0) {
        wo.frames = sim::select_frames(vehicles[k].sensor_poses.size(), real.drops,
                                       sim::hash_combine(seed, 2000 + k));
        spdlog::info("{}: {} of {} frames kept", dir, wo.frames.size(),
                     vehicles[k].sensor_poses.size());
      }
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
          simulated.add(sim::compute_scan_statistics(c, model.elevations_deg));
        };
      }
      const auto r = sim::write_sequence(dir, raycaster, vehicles[k].sensor_poses, wo);
      raycast_s += r.raycast_seconds;
      frames_total += r.frames;
      points_total += r.points;
      if (!second_sensor.empty()) {
        // The second sensor rides on the first: its poses are the first's times the extrinsic;
        // same frames, sweep timing and traffic, its own model, noise seed and no self-hits.
        std::vector<Eigen::Isometry3d> poses;
        for (const Eigen::Isometry3d& p : vehicles[k].sensor_poses)
          poses.push_back(p * second_in_first);
        sim::SequenceWriteOptions wo2 = wo;
        wo2.model = *sim::LidarModel::from_name(second_sensor);
        if (noise >= 0) wo2.model.range_noise_sigma = noise;
        if (dropout >= 0) wo2.model.dropout = dropout;
        wo2.model.validate();
        wo2.seed = sim::hash_combine(seed, 5000 + k);
        wo2.rig.body = sim::EgoBody();
        wo2.on_scan = nullptr;
        wo2.progress = nullptr;
        const auto r2 = sim::write_sequence(second_output, raycaster, poses, wo2);
        write_extrinsic(second_output, second_in_first,
                        second_extrinsic.empty() ? "0,0,0,0,0,0" : second_extrinsic);
        spdlog::info("second sensor {}: {} frames, {:.0f} points/frame into {}", second_sensor,
                     r2.frames, static_cast<double>(r2.points) / r2.frames, second_output);
      }
    }
    spdlog::info("done: {} frames, {:.0f} points/frame, ray casting {:.1f} ms/frame ({} threads)",
                 frames_total, static_cast<double>(points_total) / frames_total,
                 1000.0 * raycast_s / frames_total,
                 tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));

    if (!compare_real.empty()) {
      const auto real_stats = real_statistics(compare_real, model.elevations_deg);
      std::printf("%-28s %12s %14s\n", "statistic",
                  ("real(" + std::to_string(real_stats.count()) + ")").c_str(),
                  ("sim(" + std::to_string(simulated.count()) + ")").c_str());
      for (const auto& [label, value] : real_stats.rows()) {
        std::printf("%-28s %12.3f %14.3f\n", label.c_str(), value, simulated.mean(label));
      }
    }
    return 0;
  } catch (const std::invalid_argument& e) {  // an option's value (--frames, --districts, ...)
    return litamin2::tools::usage_error(app.get_name(), e.what());
  } catch (const std::exception& e) {  // io::IoError and the rest
    return litamin2::tools::runtime_error(app.get_name(), e.what());
  }
}

#include "litamin2/sim/sequence_writer.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "litamin2/io/io_error.hpp"
#include "litamin2/io/kitti_bin.hpp"
#include "litamin2/io/kitti_calib.hpp"
#include "litamin2/io/pcd.hpp"
#include "litamin2/io/trajectory.hpp"
#include "litamin2/sim/continuous_trajectory.hpp"
#include "litamin2/sim/random.hpp"

namespace litamin2::sim {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

void write_text(const std::string& path, const std::string& text) {
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) throw io::IoError(path, "cannot open for writing");
  const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  if (std::fclose(f) != 0 || !ok) throw io::IoError(path, "write failed");
}

}  // namespace

void write_kitti_calib(const std::string& path, const Eigen::Isometry3d& velo_to_cam) {
  // P0..P3 of KITTI odometry sequence 00 (placeholders: the simulator has no cameras).
  std::string text =
      "P0: 7.188560000000e+02 0.000000000000e+00 6.071928000000e+02 0.000000000000e+00 "
      "0.000000000000e+00 7.188560000000e+02 1.852157000000e+02 0.000000000000e+00 "
      "0.000000000000e+00 0.000000000000e+00 1.000000000000e+00 0.000000000000e+00\n"
      "P1: 7.188560000000e+02 0.000000000000e+00 6.071928000000e+02 -3.861448000000e+02 "
      "0.000000000000e+00 7.188560000000e+02 1.852157000000e+02 0.000000000000e+00 "
      "0.000000000000e+00 0.000000000000e+00 1.000000000000e+00 0.000000000000e+00\n"
      "P2: 7.188560000000e+02 0.000000000000e+00 6.071928000000e+02 4.538225000000e+01 "
      "0.000000000000e+00 7.188560000000e+02 1.852157000000e+02 -1.130887000000e-01 "
      "0.000000000000e+00 0.000000000000e+00 1.000000000000e+00 3.779761000000e-03\n"
      "P3: 7.188560000000e+02 0.000000000000e+00 6.071928000000e+02 -3.372877000000e+02 "
      "0.000000000000e+00 7.188560000000e+02 1.852157000000e+02 2.369057000000e+00 "
      "0.000000000000e+00 0.000000000000e+00 1.000000000000e+00 4.915215000000e-03\n";
  text += "Tr:";
  const Eigen::Matrix<double, 3, 4> m = velo_to_cam.matrix().topRows<3>();
  char buf[64];
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) {
      std::snprintf(buf, sizeof(buf), " %.12e", m(r, c));
      text += buf;
    }
  }
  text += "\n";
  write_text(path, text);
}

namespace {

/// The scan's points with their time and ring as a binary PCD.
void write_sweep_pcd(const std::string& path, const SimulatedScan& scan) {
  io::PcdField t{"t", 'F', 4, std::vector<double>(scan.times.begin(), scan.times.end())};
  io::PcdField ring{"ring", 'U', 2, std::vector<double>(scan.rings.begin(), scan.rings.end())};
  io::write_pcd_binary(path, scan.cloud, {t, ring});
}

/// The poses to write: `frames`, or every index; checked to be increasing and in range.
std::vector<std::size_t> frames_to_write(const std::vector<std::size_t>& frames, std::size_t n) {
  if (frames.empty()) {
    std::vector<std::size_t> all(n);
    for (std::size_t i = 0; i < n; ++i) all[i] = i;
    return all;
  }
  for (std::size_t k = 0; k < frames.size(); ++k) {
    if (frames[k] >= n || (k > 0 && frames[k] <= frames[k - 1])) {
      throw std::invalid_argument("write_sequence: frames must be increasing indices below " +
                                  std::to_string(n));
    }
  }
  return frames;
}

}  // namespace

SequenceWriteResult write_sequence(const std::string& dir, Raycaster& raycaster,
                                   const std::vector<Eigen::Isometry3d>& sensor_poses,
                                   const SequenceWriteOptions& options) {
  if (sensor_poses.empty()) throw std::invalid_argument("write_sequence: no poses");
  options.rig.validate();
  const std::vector<std::size_t> frames = frames_to_write(options.frames, sensor_poses.size());
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(fs::path(dir) / "velodyne", ec);
  if (!ec && options.write_pcd) fs::create_directories(fs::path(dir) / "pcd", ec);
  if (ec) throw io::IoError(dir, "cannot create folder: " + ec.message());
  const ContinuousTrajectory trajectory(sensor_poses, options.frame_period);
  SequenceWriteResult result;
  std::string times, sources;
  std::vector<Eigen::Isometry3d> written;
  char name[32];
  for (std::size_t out = 0; out < frames.size(); ++out) {
    const std::size_t i = frames[out];
    auto t0 = Clock::now();
    SweepRequest request;
    request.start = sensor_poses[i];
    request.start_time = static_cast<double>(i) * options.frame_period;
    request.end = options.rig.sweep.motion
                      ? trajectory.pose_at(request.start_time + options.rig.sweep.duration)
                      : request.start;
    request.traffic = options.traffic;
    const SimulatedScan scan =
        raycaster.scan(request, options.model, options.rig, hash_combine(options.seed, i));
    result.raycast_seconds += seconds_since(t0);
    t0 = Clock::now();
    std::snprintf(name, sizeof(name), "%06zu.bin", out);
    io::write_kitti_bin((fs::path(dir) / "velodyne" / name).string(), scan.cloud);
    if (options.write_pcd) {
      std::snprintf(name, sizeof(name), "%06zu.pcd", out);
      write_sweep_pcd((fs::path(dir) / "pcd" / name).string(), scan);
    }
    result.write_seconds += seconds_since(t0);
    result.points += scan.cloud.size();
    if (options.on_scan) options.on_scan(out, scan.cloud);
    if (options.on_sweep) options.on_sweep(out, scan);
    ++result.frames;
    std::snprintf(name, sizeof(name), "%e\n",
                  static_cast<double>(i - frames.front()) * options.frame_period);
    times += name;
    std::snprintf(name, sizeof(name), "%zu\n", i);
    sources += name;
    written.push_back(sensor_poses[i]);
    if (options.progress) options.progress(out + 1, frames.size());
  }
  io::write_kitti_poses((fs::path(dir) / "poses.txt").string(),
                        io::velo_to_cam_trajectory(written, options.velo_to_cam));
  Eigen::Isometry3d sensor_to_cam = options.velo_to_cam;
  if (!options.rig.mount.is_identity()) sensor_to_cam.linear() *= options.rig.mount.rotation();
  write_kitti_calib((fs::path(dir) / "calib.txt").string(), sensor_to_cam);
  write_text((fs::path(dir) / "times.txt").string(), times);
  if (!options.frames.empty()) write_text((fs::path(dir) / "source_frames.txt").string(), sources);
  return result;
}

}  // namespace litamin2::sim

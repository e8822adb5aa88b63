#include "litamin2/sim/sequence_writer.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "litamin2/io/io_error.hpp"
#include "litamin2/io/kitti_bin.hpp"
#include "litamin2/io/kitti_calib.hpp"
#include "litamin2/io/trajectory.hpp"
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

SequenceWriteResult write_sequence(const std::string& dir, Raycaster& raycaster,
                                   const std::vector<Eigen::Isometry3d>& sensor_poses,
                                   const SequenceWriteOptions& options) {
  if (sensor_poses.empty()) throw std::invalid_argument("write_sequence: no poses");
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(fs::path(dir) / "velodyne", ec);
  if (ec) throw io::IoError(dir, "cannot create folder: " + ec.message());
  SequenceWriteResult result;
  std::string times;
  char name[32];
  for (std::size_t i = 0; i < sensor_poses.size(); ++i) {
    auto t0 = Clock::now();
    const PointCloud cloud =
        raycaster.scan(sensor_poses[i], options.model, hash_combine(options.seed, i));
    result.raycast_seconds += seconds_since(t0);
    t0 = Clock::now();
    std::snprintf(name, sizeof(name), "%06zu.bin", i);
    io::write_kitti_bin((fs::path(dir) / "velodyne" / name).string(), cloud);
    result.write_seconds += seconds_since(t0);
    result.points += cloud.size();
    if (options.on_scan) options.on_scan(i, cloud);
    ++result.frames;
    std::snprintf(name, sizeof(name), "%e\n", static_cast<double>(i) * options.frame_period);
    times += name;
    if (options.progress) options.progress(i + 1, sensor_poses.size());
  }
  io::write_kitti_poses((fs::path(dir) / "poses.txt").string(),
                        io::velo_to_cam_trajectory(sensor_poses, options.velo_to_cam));
  write_kitti_calib((fs::path(dir) / "calib.txt").string(), options.velo_to_cam);
  write_text((fs::path(dir) / "times.txt").string(), times);
  return result;
}

}  // namespace litamin2::sim

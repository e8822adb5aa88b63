#pragma once
/// Writing simulated scans as a KITTI odometry sequence folder.

#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "litamin2/sim/lidar_model.hpp"
#include "litamin2/sim/raycaster.hpp"

namespace litamin2::sim {

/// Options of write_sequence.
struct SequenceWriteOptions {
  /// Sensor to simulate.
  LidarModel model = LidarModel::hdl64();
  /// Seed of the scan noise; frame i uses hash(seed, i).
  std::uint64_t seed = 0;
  /// Tr (velodyne -> camera 0) written to calib.txt and used for poses.txt.
  Eigen::Isometry3d velo_to_cam = Eigen::Isometry3d::Identity();
  /// Time between frames, seconds (times.txt).
  double frame_period = 0.1;
  /// Called after each frame with (frames done, total); may be empty.
  std::function<void(std::size_t, std::size_t)> progress;
  /// Called with (frame index, scan) after each scan is simulated; may be empty.
  std::function<void(std::size_t, const PointCloud&)> on_scan;
};

/// What write_sequence produced.
struct SequenceWriteResult {
  /// Frames written.
  std::size_t frames = 0;
  /// Points written over all frames.
  std::size_t points = 0;
  /// Wall time spent preparing scenes and casting rays, seconds.
  double raycast_seconds = 0.0;
  /// Wall time spent writing files, seconds.
  double write_seconds = 0.0;
};

/// Simulates one scan per sensor pose (world frame, z up) and writes the KITTI odometry layout:
/// `dir/velodyne/NNNNNN.bin` (x, y, z, intensity float32), `dir/poses.txt` (ground truth in the
/// camera-0 convention relative to the first frame: Tr * V0^-1 * Vi * Tr^-1), `dir/calib.txt`
/// (P0..P3 of KITTI 00 as placeholders and the "Tr:" line) and `dir/times.txt`. Creates the
/// folders. Throws io::IoError if a file cannot be written, std::invalid_argument for no poses.
SequenceWriteResult write_sequence(const std::string& dir, Raycaster& raycaster,
                                   const std::vector<Eigen::Isometry3d>& sensor_poses,
                                   const SequenceWriteOptions& options);

/// Writes a KITTI calib.txt with placeholder P0..P3 (KITTI 00's) and the given Tr.
void write_kitti_calib(const std::string& path, const Eigen::Isometry3d& velo_to_cam);

}  // namespace litamin2::sim

#pragma once
/// Writing simulated scans as a KITTI odometry sequence folder.

#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "litamin2/sim/lidar_model.hpp"
#include "litamin2/sim/raycaster.hpp"
#include "litamin2/sim/sensor_rig.hpp"
#include "litamin2/sim/simulated_scan.hpp"
#include "litamin2/sim/traffic.hpp"

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
  /// Installation of the sensor: sweep timing and motion within it, mount tilt, self-hits.
  SensorRig rig;
  /// Moving actors on the poses' clock (pose i at i * frame_period), or null for none.
  const Traffic* traffic = nullptr;
  /// Indices of the poses to write (strictly increasing; dropped frames are the missing
  /// ones); empty = every pose. Frame files are numbered consecutively.
  std::vector<std::size_t> frames;
  /// Also write `dir/pcd/NNNNNN.pcd`: binary PCD with x y z intensity (F 4), t (F 4, seconds
  /// from the sweep start) and ring (U 2, 0 = lowest beam), the same points as the .bin.
  bool write_pcd = false;
  /// Called after each frame with (frames done, total); may be empty.
  std::function<void(std::size_t, std::size_t)> progress;
  /// Called with (frame index, scan) after each scan is simulated; may be empty.
  std::function<void(std::size_t, const PointCloud&)> on_scan;
  /// Called with (frame index, scan with times and rings) after each scan; may be empty.
  std::function<void(std::size_t, const SimulatedScan&)> on_sweep;
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

/// Simulates one scan per sensor pose (world frame, z up; with a tilted mount these are the
/// vehicle poses and the sensor is rotated on them) and writes the KITTI odometry layout:
/// `dir/velodyne/NNNNNN.bin` (x, y, z, intensity float32), `dir/poses.txt` (ground truth in the
/// camera-0 convention relative to the first frame: Tr * V0^-1 * Vi * Tr^-1), `dir/calib.txt`
/// (P0..P3 of KITTI 00 as placeholders and the "Tr:" line) and `dir/times.txt`. Creates the
/// folders.
///
/// Frame i's sweep starts at time i * frame_period, at pose i, and lasts the rig's sweep
/// duration; with sweep motion it is cast along the poses interpolated in SE(3)
/// (ContinuousTrajectory; the last sweep extrapolates at constant velocity) and each point is in
/// the sensor frame of its firing (raw, not deskewed). The ground truth of a frame is the pose at
/// its sweep start, as drivers stamp a scan's header with the sweep start. With a tilted mount,
/// calib.txt holds Tr * M (M the mount rotation: sensor to vehicle), so Tr' * S0^-1 * Si * Tr'^-1
/// of the tilted sensor poses Si = Vi * M is the same ground truth. With `frames`, times.txt holds
/// the kept frames' times (from the first kept one) and `dir/source_frames.txt` the index of the
/// pose each file was simulated at. Throws io::IoError if a file cannot be written,
/// std::invalid_argument for no poses, bad frame indices or an invalid rig.
SequenceWriteResult write_sequence(const std::string& dir, Raycaster& raycaster,
                                   const std::vector<Eigen::Isometry3d>& sensor_poses,
                                   const SequenceWriteOptions& options);

/// Writes a KITTI calib.txt with placeholder P0..P3 (KITTI 00's) and the given Tr.
void write_kitti_calib(const std::string& path, const Eigen::Isometry3d& velo_to_cam);

}  // namespace litamin2::sim

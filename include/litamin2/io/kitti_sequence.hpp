#pragma once
/// A sequence of LiDAR scans on disk: a KITTI odometry sequence folder or a plain folder of
/// .bin / .pcd scans.

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "litamin2/core/point_cloud.hpp"
#include "litamin2/io/kitti_bin.hpp"

namespace litamin2::io {

/// Scans of one sequence, in name order, with optional calibration, timestamps and ground truth.
///
/// A folder containing `velodyne/` is a KITTI odometry sequence:
///  - scans: velodyne/*.bin in (byte-wise) file-name order (or pcd/*.pcd, see the constructor);
///  - `calib.txt` if present -> velo_to_cam() (see read_kitti_velo_to_cam);
///  - `times.txt` if present -> timestamps (one number per line; the count must equal the number
///    of scans), else scan i is at i * 0.1 s;
///  - ground truth, optional: `poses.txt` in the folder, else `<dataset>/poses/XX.txt` when the
///    folder is `<dataset>/sequences/XX`; its pose count must equal the number of scans.
/// Any other folder is a plain folder: its *.bin and *.pcd files (extension case-insensitive) in
/// file-name order, timestamps i * 0.1 s, no calibration and no ground truth.
/// Only file names and metadata are read on construction; scans are read by load().
class ScanSequence {
 public:
  /// Opens a folder. Throws IoError if it does not exist, is not a folder, holds no scans, or
  /// if times.txt / calib.txt / ground truth are present but unreadable or inconsistent.
  /// With `pcd_scans`, a KITTI sequence folder's scans are its pcd/*.pcd files instead of
  /// velodyne/*.bin (litamin2-sim --sweep-motion writes the same scans there with per-point
  /// times); times, calibration and ground truth stay the folder's. A folder without pcd/ is
  /// then an IoError; a plain folder is read as always.
  explicit ScanSequence(const std::string& folder, const KittiBinOptions& bin_options = {},
                        bool pcd_scans = false);

  /// Number of scans.
  std::size_t size() const { return paths_.size(); }
  /// True for a KITTI odometry sequence folder (one with velodyne/), false for a plain folder.
  bool is_kitti() const { return is_kitti_; }
  /// The folder given to the constructor.
  const std::string& folder() const { return folder_; }
  /// Options used by load() for .bin scans.
  const KittiBinOptions& bin_options() const { return bin_options_; }

  /// Path of scan i. Throws std::out_of_range if i >= size().
  const std::string& path(std::size_t i) const;
  /// Timestamp of scan i in seconds. Throws std::out_of_range if i >= size().
  double timestamp(std::size_t i) const;
  /// Reads scan i (.bin with bin_options(), .pcd with read_pcd). Throws std::out_of_range if
  /// i >= size(), IoError if the file is unreadable or corrupt.
  PointCloud load(std::size_t i) const;

  /// Tr (Velodyne -> camera 0) from calib.txt, if the sequence has one.
  const std::optional<Eigen::Isometry3d>& velo_to_cam() const { return velo_to_cam_; }
  /// Ground-truth camera-0 poses (KITTI convention), one per scan, if available.
  const std::optional<std::vector<Eigen::Isometry3d>>& ground_truth_cam() const {
    return ground_truth_cam_;
  }
  /// Ground truth converted to Velodyne poses relative to the first scan (needs both ground
  /// truth and calibration; std::nullopt otherwise). See cam_to_velo_trajectory.
  std::optional<std::vector<Eigen::Isometry3d>> ground_truth_velo() const;

 private:
  std::string folder_;
  KittiBinOptions bin_options_;
  bool is_kitti_ = false;
  std::vector<std::string> paths_;
  std::vector<double> timestamps_;
  std::optional<Eigen::Isometry3d> velo_to_cam_;
  std::optional<std::vector<Eigen::Isometry3d>> ground_truth_cam_;
};

}  // namespace litamin2::io

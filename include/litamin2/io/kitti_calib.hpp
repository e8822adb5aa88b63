#pragma once
/// KITTI odometry calibration (Tr: Velodyne -> left rectified camera 0) and the conversions
/// between camera-0 trajectories (the ground truth convention) and Velodyne trajectories.

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

namespace litamin2::io {

/// Reads Tr, the transform taking Velodyne points into camera-0 coordinates
/// (p_cam = Tr * p_velo), from one of:
///  - a KITTI odometry sequence calib.txt ("P0: ..." ... "Tr: <12 numbers>"), or the raw-data
///    style "Tr_velo_to_cam: <12 numbers>", or a raw-data calib_velo_to_cam.txt ("R: <9>",
///    "T: <3>"); `sequence` is ignored for these;
///  - a folder: its calib.txt is read as above;
///  - a per-sequence table like shared/data/kitti/calib_Tr_velo_to_cam.txt: lines
///    "<first>[-<last>]: <12 numbers>" (e.g. "00-02: ...", "03: ...") and '#' comments; then
///    `sequence` (e.g. 0 for "00") is required and selects the row whose range contains it.
/// The 12 numbers are the row-major 3x4 matrix [R|t]. Throws IoError naming the file if it is
/// missing/unreadable, has no usable entry, lacks a row for the sequence, needs a sequence that
/// was not given, has a malformed entry, a rotation part that is not orthonormal
/// (checks::kOrthonormalTolerance) or is a reflection (determinant -1), or a translation beyond
/// checks::kMaxPosition.
Eigen::Isometry3d read_kitti_velo_to_cam(const std::string& path,
                                         std::optional<int> sequence = std::nullopt);

/// Parses a KITTI sequence name such as "00", "7", "10", or a path ending in one
/// (".../sequences/05"). Throws std::invalid_argument if it is not a non-negative integer.
int kitti_sequence_number(const std::string& name);

/// Converts one camera-0 pose to the Velodyne frame: Tr^-1 * pose_cam * Tr.
Eigen::Isometry3d cam_pose_to_velo(const Eigen::Isometry3d& pose_cam,
                                   const Eigen::Isometry3d& velo_to_cam);

/// Converts one Velodyne pose to the camera-0 frame: Tr * pose_velo * Tr^-1.
Eigen::Isometry3d velo_pose_to_cam(const Eigen::Isometry3d& pose_velo,
                                   const Eigen::Isometry3d& velo_to_cam);

/// Converts a camera-0 trajectory (e.g. KITTI ground truth) into a Velodyne trajectory relative
/// to its first pose: out[i] = Tr^-1 * (P[0]^-1 * P[i]) * Tr, so out[0] is the identity. For
/// KITTI ground truth P[0] is already the identity.
std::vector<Eigen::Isometry3d> cam_to_velo_trajectory(const std::vector<Eigen::Isometry3d>& cam,
                                                      const Eigen::Isometry3d& velo_to_cam);

/// Converts a Velodyne trajectory (e.g. odometry output) into a camera-0 trajectory relative to
/// its first pose, comparable with KITTI ground truth: out[i] = Tr * (V[0]^-1 * V[i]) * Tr^-1.
std::vector<Eigen::Isometry3d> velo_to_cam_trajectory(const std::vector<Eigen::Isometry3d>& velo,
                                                      const Eigen::Isometry3d& velo_to_cam);

}  // namespace litamin2::io

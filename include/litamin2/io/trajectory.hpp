#pragma once
/// Trajectory files: KITTI odometry poses (12 numbers per line) and TUM (t x y z qx qy qz qw).

#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace litamin2::io {

/// A pose with a timestamp (seconds).
struct TimedPose {
  /// Timestamp in seconds.
  double time = 0;
  /// Pose (sensor to world).
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
};

/// Reads a KITTI pose file: one line per frame holding the row-major 3x4 matrix [R|t] as 12
/// numbers. CRLF line ends and trailing blank lines are accepted; the matrix is taken as is (not
/// re-orthonormalised). Throws IoError naming the file and the 1-based line number for a line
/// with the wrong number of values, a non-number, NaN/Inf, a rotation that is not orthonormal
/// within checks::kOrthonormalTolerance or is a reflection, a translation beyond
/// checks::kMaxPosition, or a blank line followed by more data, and IoError for a
/// missing/unreadable file or one without any pose.
std::vector<Eigen::Isometry3d> read_kitti_poses(const std::string& path);

/// Writes a KITTI pose file (12 values per line, "%.16e", i.e. lossless double precision, LF line
/// ends). Throws IoError if the file cannot be written.
void write_kitti_poses(const std::string& path, const std::vector<Eigen::Isometry3d>& poses);

/// Reads a TUM trajectory: "t x y z qx qy qz qw" per line; lines starting with '#' and blank lines
/// are skipped, CRLF accepted. A quaternion must be a unit quaternion within
/// checks::kOrthonormalTolerance (the rounding of its digits is then removed); a zero,
/// unnormalised or non-finite quaternion, a non-finite time, a translation beyond
/// checks::kMaxPosition, a line with a count other than 8 or a non-number throws IoError naming
/// file and line number; so does a file without any pose.
std::vector<TimedPose> read_tum(const std::string& path);

/// Writes a TUM trajectory ("%.17g" time, "%.16e" values: lossless). The quaternion written is the
/// one of the pose's rotation part (normalised, qw >= 0). Throws IoError if the file cannot be
/// written.
void write_tum(const std::string& path, const std::vector<TimedPose>& poses);

}  // namespace litamin2::io

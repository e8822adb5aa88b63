#pragma once
/// KITTI Velodyne scans (.bin): flat little-endian float32 records, either x,y,z,intensity
/// (the official KITTI layout, 16 bytes per point) or x,y,z only (12 bytes per point, as
/// written by some tools).

#include <string>

#include "litamin2/core/point_cloud.hpp"

namespace litamin2::io {

/// Record layout of a .bin scan.
enum class KittiBinLayout {
  /// Decide from the file: size a multiple of 16 only -> XYZI; of 12 only -> XYZ; of both
  /// (i.e. of 48) -> the interpretation that is plausible (see read_kitti_bin).
  kAuto,
  /// x, y, z, intensity as float32 (official KITTI).
  kXYZI,
  /// x, y, z as float32, no intensity.
  kXYZ,
};

/// Options of read_kitti_bin.
struct KittiBinOptions {
  /// Record layout; Auto detects it from the file size and content.
  KittiBinLayout layout = KittiBinLayout::kAuto;
  /// Vertical intrinsic-calibration correction in degrees, as applied by KISS-ICP and CT-ICP to
  /// KITTI HDL-64 scans (they use 0.205): every point p is rotated by this angle about the axis
  /// p x (0,0,1), which tilts it upwards while keeping its range and azimuth. 0 (the default)
  /// leaves points untouched. Points on the z axis are left unchanged.
  double vertical_angle_correction_deg = 0.0;
};

/// Reads a KITTI .bin scan. Points with a non-finite (NaN/Inf) coordinate are dropped, together
/// with their intensity, so the result only holds finite points. With layout XYZ (given or
/// detected) the cloud has no intensities. A point with finite coordinates and a NaN/Inf
/// intensity, or one the vertical angle correction pushes to Inf, is an IoError (rejected, not
/// repaired).
///
/// Auto detection when the size is a multiple of 48 bytes (both layouts possible): a record
/// read as XYZI is "bad" if a coordinate is not finite or its intensity is not in [0, 256); a
/// record read as XYZ is bad if a coordinate is not finite. The layout with the smaller fraction
/// of bad records wins; on a tie (typically both zero) the layout whose consecutive points are
/// closer to each other (median distance; real scans are stored in scan order) wins, XYZI on an
/// exact tie. Throws IoError if the file is missing/unreadable/empty or its size fits neither
/// layout (or the layout given).
PointCloud read_kitti_bin(const std::string& path, const KittiBinOptions& options = {});

/// Applies the vertical angle correction of KittiBinOptions (in degrees) to every point, in place.
/// Throws std::range_error naming the point if a corrected point leaves the float range (its
/// coordinates were within a hair of it).
void apply_vertical_angle_correction(PointCloud& cloud, double angle_deg);

/// Writes a KITTI .bin scan as x,y,z,intensity float32 records; intensity is 0 when the cloud
/// has none. Throws IoError if the file cannot be written, std::invalid_argument if the cloud
/// has intensities but not one per point.
void write_kitti_bin(const std::string& path, const PointCloud& cloud);

}  // namespace litamin2::io

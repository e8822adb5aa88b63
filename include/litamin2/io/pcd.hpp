#pragma once
/// Point Cloud Library .pcd files (format v0.7 and the older headers PCL still reads).

#include <string>
#include <vector>

#include "litamin2/core/point_cloud.hpp"

namespace litamin2::io {

/// Reads a .pcd file with DATA ascii, binary or binary_compressed (PCL's LZF-compressed,
/// field-by-field layout, decoded with liblzf). Fields x, y, z are required (TYPE F, SIZE 4 or 8,
/// COUNT 1); a field named "intensity" (COUNT 1, any numeric TYPE/SIZE, e.g. F4, F8, U1, U2) is
/// read as intensity; every other field, including COUNT > 1 ones, is skipped. A per-point time
/// field (the first of t, time, timestamp, offset_time present: Ouster, Velodyne, Hesai, Livox
/// names; COUNT 1) is read into PointCloud::times as seconds relative to the sweep: integer TYPEs
/// are nanoseconds, F seconds; values within +-1 s are relative already, larger ones absolute (F 8
/// or an integer SIZE 8) and made relative to the scan's earliest point. A non-finite time,
/// absolute times in F 4 or a span over 1 s throw IoError. WIDTH*HEIGHT must equal POINTS (POINTS
/// defaults to WIDTH*HEIGHT, HEIGHT to 1). Points with a non-finite coordinate (PCL's NaN points
/// of organised clouds) are dropped together with their intensity and time. Throws IoError naming
/// the file for a missing/unreadable file, a malformed header, inconsistent counts, truncated
/// data, a coordinate beyond float range, or a point with finite coordinates whose intensity is
/// NaN, Inf or beyond float range (rejected, not repaired).
PointCloud read_pcd(const std::string& path);

/// Writes a binary .pcd (v0.7, unorganised: WIDTH = size, HEIGHT = 1) with float32 fields
/// x y z, plus intensity if the cloud has intensities. Throws IoError if the file cannot be
/// written, std::invalid_argument if the cloud has intensities but not one per point.
void write_pcd_binary(const std::string& path, const PointCloud& cloud);

/// A per-point field written after x y z (and intensity) by write_pcd_binary: its PCD name,
/// TYPE ('F' float, 'U' unsigned, 'I' signed) and SIZE in bytes (F: 4 or 8; U and I: 1, 2 or
/// 4), one value per point (converted to the type; integers are rounded and clamped).
struct PcdField {
  /// Field name, e.g. "t" or "ring"; non-empty, no white space.
  std::string name;
  /// PCD TYPE letter.
  char type = 'F';
  /// PCD SIZE in bytes.
  std::size_t size = 4;
  /// One value per point.
  std::vector<double> values;
};

/// As write_pcd_binary, followed by the extra fields in their order (e.g. a per-point time
/// `t` as F 4 and `ring` as U 2, as LiDAR drivers publish them). Throws std::invalid_argument
/// for a field with a bad name, type or size, a name that repeats x/y/z/intensity or another
/// field, or not one value per point.
void write_pcd_binary(const std::string& path, const PointCloud& cloud,
                      const std::vector<PcdField>& extra);

}  // namespace litamin2::io

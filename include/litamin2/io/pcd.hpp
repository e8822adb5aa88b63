#pragma once
/// Point Cloud Library .pcd files (format v0.7 and the older headers PCL still reads).

#include <string>

#include "litamin2/core/point_cloud.hpp"

namespace litamin2::io {

/// Reads a .pcd file with DATA ascii or binary (binary_compressed is not supported and throws
/// IoError saying so). Fields x, y, z are required (TYPE F, SIZE 4 or 8, COUNT 1); a field named
/// "intensity" (COUNT 1, any numeric TYPE/SIZE, e.g. F4, F8, U1, U2) is read as intensity; every
/// other field, including COUNT > 1 ones, is skipped. WIDTH*HEIGHT must equal POINTS (POINTS
/// defaults to WIDTH*HEIGHT, HEIGHT to 1). Points with a non-finite coordinate (PCL's NaN points
/// of organised clouds) are dropped together with their intensity. Throws IoError naming the
/// file for a missing/unreadable file, a malformed header, inconsistent counts, truncated data,
/// a coordinate beyond float range, or a point with finite coordinates whose intensity is NaN,
/// Inf or beyond float range (rejected, not repaired).
PointCloud read_pcd(const std::string& path);

/// Writes a binary .pcd (v0.7, unorganised: WIDTH = size, HEIGHT = 1) with float32 fields
/// x y z, plus intensity if the cloud has intensities. Throws IoError if the file cannot be
/// written, std::invalid_argument if the cloud has intensities but not one per point.
void write_pcd_binary(const std::string& path, const PointCloud& cloud);

}  // namespace litamin2::io

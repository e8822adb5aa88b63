#pragma once
/// Stanford .ply files holding vertices with scalar properties (point clouds, voxel statistics).

#include <cstddef>
#include <string>
#include <vector>

#include "litamin2/core/point_cloud.hpp"

namespace litamin2::io {

/// Writes a binary little-endian PLY with one vertex per point and float properties x, y, z,
/// plus intensity if the cloud has intensities. Throws IoError if the file cannot be written,
/// std::invalid_argument if the cloud has intensities but not one per point.
void write_ply_points(const std::string& path, const PointCloud& cloud);

/// Writes a binary little-endian PLY with one vertex per row of `values_row_major` and one float
/// property per name, e.g. {"x","y","z","c00","c01",...,"count"} for voxel distributions.
/// values_row_major.size() must be a multiple of property_names.size(); names must be non-empty,
/// unique and free of whitespace (std::invalid_argument otherwise). Throws IoError if the file
/// cannot be written.
void write_ply_vertices(const std::string& path, const std::vector<std::string>& property_names,
                        const std::vector<float>& values_row_major);

/// The vertex element of a PLY file: property names and values, one row per vertex.
struct PlyVertices {
  /// Scalar property names of the vertex element, in file order.
  std::vector<std::string> property_names;
  /// Values, row-major: vertex i, property j is values[i * property_names.size() + j].
  std::vector<double> values;

  /// Number of vertices.
  std::size_t size() const {
    return property_names.empty() ? 0 : values.size() / property_names.size();
  }
  /// Index of a property, or -1 if there is none with that name.
  int index_of(const std::string& name) const {
    for (std::size_t j = 0; j < property_names.size(); ++j) {
      if (property_names[j] == name) return static_cast<int>(j);
    }
    return -1;
  }
  /// Value of property j of vertex i.
  double at(std::size_t i, std::size_t j) const { return values[i * property_names.size() + j]; }
};

/// Reads the "vertex" element of a PLY file (format ascii, binary_little_endian or
/// binary_big_endian; any scalar property type). Other elements, including ones with list
/// properties (faces), are skipped; list properties inside the vertex element throw IoError.
/// Throws IoError naming the file if it is missing, not a PLY, has no vertex element, has an
/// element with items but no property, or is truncated.
PlyVertices read_ply_vertices(const std::string& path);

/// Reads a PLY point cloud: vertex properties x, y, z (required) and intensity (optional).
/// Vertices with a non-finite coordinate are dropped. Throws IoError as read_ply_vertices does,
/// if x, y or z is missing, and if a coordinate is beyond float range or an intensity is not a
/// finite float (nothing is repaired).
PointCloud read_ply_points(const std::string& path);

}  // namespace litamin2::io

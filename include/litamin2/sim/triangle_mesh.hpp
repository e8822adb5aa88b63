#pragma once
/// Triangle soup with one material and reflectivity per triangle: the geometry unit of the
/// simulated world (one mesh per world tile).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <vector>

#include "litamin2/sim/material.hpp"

namespace litamin2::sim {

/// Indexed triangle mesh with per-triangle surface attributes.
struct TriangleMesh {
  /// Vertex positions in the world frame (metres, z up).
  std::vector<Eigen::Vector3f> vertices;
  /// Vertex indices of each triangle (counter-clockwise seen from outside).
  std::vector<std::array<std::uint32_t, 3>> triangles;
  /// One material per triangle.
  std::vector<Material> materials;
  /// One reflectivity in [0, 1] per triangle.
  std::vector<float> reflectivity;

  /// Number of triangles.
  std::size_t size() const { return triangles.size(); }
  /// True if the mesh has no triangles.
  bool empty() const { return triangles.empty(); }

  /// Appends a vertex and returns its index.
  std::uint32_t add_vertex(const Eigen::Vector3f& v);
  /// Appends a triangle (a, b, c) with its attributes.
  void add_triangle(const Eigen::Vector3f& a, const Eigen::Vector3f& b, const Eigen::Vector3f& c,
                    Material m, float refl);
  /// Appends the quad a-b-c-d (two triangles, a planar convex quad in order).
  void add_quad(const Eigen::Vector3f& a, const Eigen::Vector3f& b, const Eigen::Vector3f& c,
                const Eigen::Vector3f& d, Material m, float refl);
  /// Appends a box of the given full size centred at `pose` (12 triangles).
  void add_box(const Eigen::Isometry3f& pose, const Eigen::Vector3f& size, Material m, float refl);
  /// Appends a vertical cylinder (open ends, `sides` facets) from `base` up to base + height.
  void add_cylinder(const Eigen::Vector3f& base, float radius, float height, int sides, Material m,
                    float refl);
  /// Appends all triangles of another mesh.
  void append(const TriangleMesh& other);
  /// Axis-aligned bounds (min, max) of the vertices; empty mesh -> (+inf, -inf).
  std::pair<Eigen::Vector3f, Eigen::Vector3f> bounds() const;
};

}  // namespace litamin2::sim

#include "litamin2/sim/triangle_mesh.hpp"

#include <cmath>
#include <limits>

namespace litamin2::sim {

std::uint32_t TriangleMesh::add_vertex(const Eigen::Vector3f& v) {
  vertices.push_back(v);
  return static_cast<std::uint32_t>(vertices.size() - 1);
}

void TriangleMesh::add_triangle(const Eigen::Vector3f& a, const Eigen::Vector3f& b,
                                const Eigen::Vector3f& c, Material m, float refl) {
  const std::uint32_t ia = add_vertex(a), ib = add_vertex(b), ic = add_vertex(c);
  triangles.push_back({ia, ib, ic});
  materials.push_back(m);
  reflectivity.push_back(refl);
}

void TriangleMesh::add_quad(const Eigen::Vector3f& a, const Eigen::Vector3f& b,
                            const Eigen::Vector3f& c, const Eigen::Vector3f& d, Material m,
                            float refl) {
  const std::uint32_t ia = add_vertex(a), ib = add_vertex(b), ic = add_vertex(c),
                      id = add_vertex(d);
  triangles.push_back({ia, ib, ic});
  triangles.push_back({ia, ic, id});
  materials.insert(materials.end(), 2, m);
  reflectivity.insert(reflectivity.end(), 2, refl);
}

void TriangleMesh::add_box(const Eigen::Isometry3f& pose, const Eigen::Vector3f& size, Material m,
                           float refl) {
  const Eigen::Vector3f h = 0.5f * size;
  const auto base = static_cast<std::uint32_t>(vertices.size());
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3f c((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(),
                            (i & 4) ? h.z() : -h.z());
    vertices.push_back(pose * c);
  }
  static const int kFaces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                   {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : kFaces) {
    triangles.push_back({base + f[0], base + f[1], base + f[2]});
    triangles.push_back({base + f[0], base + f[2], base + f[3]});
  }
  materials.insert(materials.end(), 12, m);
  reflectivity.insert(reflectivity.end(), 12, refl);
}

void TriangleMesh::add_cylinder(const Eigen::Vector3f& base, float radius, float height, int sides,
                                Material m, float refl) {
  const auto first = static_cast<std::uint32_t>(vertices.size());
  for (int i = 0; i < sides; ++i) {
    const float a = 2.0f * static_cast<float>(M_PI) * static_cast<float>(i) / sides;
    const Eigen::Vector3f o(radius * std::cos(a), radius * std::sin(a), 0.0f);
    vertices.push_back(base + o);
    vertices.push_back(base + o + Eigen::Vector3f(0, 0, height));
  }
  for (int i = 0; i < sides; ++i) {
    const std::uint32_t a0 = first + 2 * i, a1 = a0 + 1;
    const std::uint32_t b0 = first + 2 * ((i + 1) % sides), b1 = b0 + 1;
    triangles.push_back({a0, b0, b1});
    triangles.push_back({a0, b1, a1});
  }
  materials.insert(materials.end(), 2 * sides, m);
  reflectivity.insert(reflectivity.end(), 2 * sides, refl);
}

void TriangleMesh::append(const TriangleMesh& other) {
  const auto offset = static_cast<std::uint32_t>(vertices.size());
  vertices.insert(vertices.end(), other.vertices.begin(), other.vertices.end());
  triangles.reserve(triangles.size() + other.triangles.size());
  for (const auto& t : other.triangles) {
    triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  }
  materials.insert(materials.end(), other.materials.begin(), other.materials.end());
  reflectivity.insert(reflectivity.end(), other.reflectivity.begin(), other.reflectivity.end());
}

std::pair<Eigen::Vector3f, Eigen::Vector3f> TriangleMesh::bounds() const {
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(std::numeric_limits<float>::infinity());
  Eigen::Vector3f hi = -lo;
  for (const auto& v : vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  return {lo, hi};
}

}  // namespace litamin2::sim

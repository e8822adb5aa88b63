#include "litamin2/sim/world_object.hpp"

#include <algorithm>
#include <cmath>

#include "litamin2/sim/random.hpp"

namespace litamin2::sim {
namespace {

using V3 = Eigen::Vector3f;

/// Local-to-world transform of an object.
struct Frame {
  Eigen::Isometry3f pose;
  V3 operator()(float x, float y, float z) const { return pose * V3(x, y, z); }
};

Frame frame_of(const WorldObject& o) {
  Eigen::Isometry3f pose = Eigen::Isometry3f::Identity();
  pose.translation() = V3(static_cast<float>(o.center.x()), static_cast<float>(o.center.y()),
                          static_cast<float>(o.ground_z));
  pose.linear() = Eigen::AngleAxisf(static_cast<float>(o.yaw), V3::UnitZ()).toRotationMatrix();
  return {pose};
}

/// Box given by local min/max corners.
void local_box(const Frame& f, const V3& lo, const V3& hi, TriangleMesh& mesh, Material m,
               float refl) {
  Eigen::Isometry3f p = f.pose;
  p.translate(0.5f * (lo + hi));
  mesh.add_box(p, hi - lo, m, refl);
}

/// Hexahedron from 8 local corners: bottom face c[0..3], top face c[4..7] (same order).
void local_hexahedron(const Frame& f, const V3 (&c)[8], TriangleMesh& mesh, Material side,
                      Material top, float refl) {
  V3 w[8];
  for (int i = 0; i < 8; ++i) w[i] = f.pose * c[i];
  mesh.add_quad(w[4], w[5], w[6], w[7], top, refl);
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 1) % 4;
    mesh.add_quad(w[i], w[j], w[j + 4], w[i + 4], side, refl);
  }
}

/// Random unit vector.
V3 random_unit(Rng& rng) {
  const double z = rng.uniform(-1.0, 1.0);
  const double a = rng.uniform(0.0, 2.0 * M_PI);
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return V3(static_cast<float>(r * std::cos(a)), static_cast<float>(r * std::sin(a)),
            static_cast<float>(z));
}

/// Irregular clutter: `count` small random triangles at random points of an ellipsoid
/// (centre c, radii r) biased towards its surface, like foliage.
void clutter_ellipsoid(const Frame& f, const V3& c, const V3& r, int count, float tri_min,
                       float tri_max, Rng& rng, TriangleMesh& mesh, Material m, float refl) {
  for (int i = 0; i < count; ++i) {
    const V3 d = random_unit(rng);
    const float s = static_cast<float>(0.55 + 0.45 * std::sqrt(rng.uniform()));
    const V3 p = c + s * d.cwiseProduct(r);
    const float size = static_cast<float>(rng.uniform(tri_min, tri_max));
    const V3 a = p + size * random_unit(rng);
    const V3 b = p + size * random_unit(rng);
    const V3 e = p + size * random_unit(rng);
    const float rv = refl * static_cast<float>(rng.uniform(0.7, 1.3));
    mesh.add_triangle(f.pose * a, f.pose * b, f.pose * e, m, std::min(rv, 1.0f));
  }
}

/// Clutter in an axis-aligned local box (hedges), biased to its outer layer.
void clutter_box(const Frame& f, const V3& lo, const V3& hi, int count, float tri_min,
                 float tri_max, Rng& rng, TriangleMesh& mesh, Material m, float refl) {
  const V3 c = 0.5f * (lo + hi), h = 0.5f * (hi - lo);
  for (int i = 0; i < count; ++i) {
    V3 u(static_cast<float>(rng.uniform(-1, 1)), static_cast<float>(rng.uniform(-1, 1)),
         static_cast<float>(rng.uniform(-1, 1)));
    const int axis = rng.uniform_int(0, 2);  // push one coordinate towards the surface
    u[axis] = (u[axis] < 0 ? -1.0f : 1.0f) * static_cast<float>(0.75 + 0.25 * rng.uniform());
    const V3 p = c + u.cwiseProduct(h);
    const float size = static_cast<float>(rng.uniform(tri_min, tri_max));
    mesh.add_triangle(f.pose * (p + size * random_unit(rng)),
                      f.pose * (p + size * random_unit(rng)),
                      f.pose * (p + size * random_unit(rng)), m,
                      std::min(1.0f, refl * static_cast<float>(rng.uniform(0.7, 1.3))));
  }
}

int clutter_count(double area, double tri_area, double coverage) {
  return std::clamp(static_cast<int>(coverage * area / tri_area), 20, 4000);
}

/// Front facade (plane y = -hy) with a grid of recessed windows and optional relief.
void building_facade(const Frame& f, float hx, float hy, float z0, float height, Rng& rng,
                     TriangleMesh& mesh, float wall_refl) {
  const float y = -hy;
  const float floor_h = static_cast<float>(rng.uniform(2.8, 3.6));
  const float col_w = static_cast<float>(rng.uniform(2.4, 4.0));
  const int floors = std::max(1, static_cast<int>(height / floor_h));
  const int cols = std::max(1, static_cast<int>((2 * hx - 1.0f) / col_w));
  const float x_start = -cols * col_w * 0.5f;
  const float win_w = col_w * static_cast<float>(rng.uniform(0.4, 0.7));
  const float win_h = floor_h * static_cast<float>(rng.uniform(0.4, 0.6));
  const float sill = static_cast<float>(rng.uniform(0.8, 1.0));
  const float depth = static_cast<float>(rng.uniform(0.15, 0.4));
  const bool shop_floor = rng.chance(0.4);
  const bool balconies = rng.chance(0.4);
  const bool cornices = rng.chance(0.5);
  const bool pilasters = rng.chance(0.35);
  const Material wall = Material::kWall;
  // Plain strips left and right of the window grid, and above the top floor.
  mesh.add_quad(f(-hx, y, z0), f(x_start, y, z0), f(x_start, y, height), f(-hx, y, height), wall,
                wall_refl);
  mesh.add_quad(f(-x_start, y, z0), f(hx, y, z0), f(hx, y, height), f(-x_start, y, height), wall,
                wall_refl);
  const float grid_top = floors * floor_h;
  if (grid_top < height) {
    mesh.add_quad(f(x_start, y, grid_top), f(-x_start, y, grid_top), f(-x_start, y, height),
                  f(x_start, y, height), wall, wall_refl);
  }
  // The cells start at z = 0 (ground); below it the wall reaches down to z0 (buried).
  mesh.add_quad(f(x_start, y, z0), f(-x_start, y, z0), f(-x_start, y, 0), f(x_start, y, 0), wall,
                wall_refl);
  for (int fl = 0; fl < floors; ++fl) {
    const float zb = fl * floor_h, zt = zb + floor_h;
    for (int c = 0; c < cols; ++c) {
      const float xl = x_start + c * col_w, xr = xl + col_w;
      const bool shop = shop_floor && fl == 0;
      const bool blank = !shop && rng.chance(0.08);
      if (blank) {
        mesh.add_quad(f(xl, y, zb), f(xr, y, zb), f(xr, y, zt), f(xl, y, zt), wall, wall_refl);
        continue;
      }
      const float ww = shop ? col_w * 0.85f : win_w;
      const float wb = shop ? zb + 0.4f : zb + sill;
      const float wt = shop ? zt - 0.5f : std::min(zt - 0.25f, wb + win_h);
      const float wl = 0.5f * (xl + xr) - 0.5f * ww, wr = wl + ww;
      const float d = shop ? depth + 0.3f : depth;
      // Wall around the window.
      mesh.add_quad(f(xl, y, zb), f(xr, y, zb), f(xr, y, wb), f(xl, y, wb), wall, wall_refl);
      mesh.add_quad(f(xl, y, wt), f(xr, y, wt), f(xr, y, zt), f(xl, y, zt), wall, wall_refl);
      mesh.add_quad(f(xl, y, wb), f(wl, y, wb), f(wl, y, wt), f(xl, y, wt), wall, wall_refl);
      mesh.add_quad(f(wr, y, wb), f(xr, y, wb), f(xr, y, wt), f(wr, y, wt), wall, wall_refl);
      // Jambs and the glass at the back of the recess.
      const float yb = y + d;
      mesh.add_quad(f(wl, y, wb), f(wr, y, wb), f(wr, yb, wb), f(wl, yb, wb), wall, wall_refl);
      mesh.add_quad(f(wl, y, wt), f(wr, y, wt), f(wr, yb, wt), f(wl, yb, wt), wall, wall_refl);
      mesh.add_quad(f(wl, y, wb), f(wl, yb, wb), f(wl, yb, wt), f(wl, y, wt), wall, wall_refl);
      mesh.add_quad(f(wr, y, wb), f(wr, yb, wb), f(wr, yb, wt), f(wr, y, wt), wall, wall_refl);
      mesh.add_quad(f(wl, yb, wb), f(wr, yb, wb), f(wr, yb, wt), f(wl, yb, wt), Material::kGlass,
                    0.1f);
      if (balconies && fl > 0 && c % 2 == 0 && fl < floors) {
        const float bd = static_cast<float>(rng.uniform(0.9, 1.5));
        local_box(f, V3(xl + 0.1f, y - bd, zb - 0.15f), V3(xr - 0.1f, y, zb), mesh,
                  Material::kConcrete, 0.35f);
        local_box(f, V3(xl + 0.1f, y - bd, zb), V3(xr - 0.1f, y - bd + 0.06f, zb + 1.0f), mesh,
                  Material::kMetal, 0.4f);
        local_box(f, V3(xl + 0.1f, y - bd, zb), V3(xl + 0.16f, y, zb + 1.0f), mesh,
                  Material::kMetal, 0.4f);
        local_box(f, V3(xr - 0.16f, y - bd, zb), V3(xr - 0.1f, y, zb + 1.0f), mesh,
                  Material::kMetal, 0.4f);
      }
    }
    if (cornices && fl > 0) {
      const float out = static_cast<float>(rng.uniform(0.08, 0.3));
      local_box(f, V3(-hx, y - out, zb - 0.2f), V3(hx, y, zb), mesh, Material::kConcrete,
                wall_refl * 0.9f);
    }
  }
  if (pilasters) {
    for (int c = 0; c <= cols; c += 2) {
      const float x = x_start + c * col_w;
      local_box(f, V3(x - 0.2f, y - 0.2f, z0), V3(x + 0.2f, y, height), mesh, Material::kWall,
                wall_refl);
    }
  }
  // Parapet / roof edge.
  local_box(f, V3(-hx, y - 0.25f, height), V3(hx, y + 0.3f, height + 0.6f), mesh,
            Material::kConcrete, 0.3f);
}

void build_building(const WorldObject& o, Rng& rng, TriangleMesh& mesh) {
  const Frame f = frame_of(o);
  const float hx = 0.5f * static_cast<float>(o.size.x()),
              hy = 0.5f * static_cast<float>(o.size.y());
  const float h = static_cast<float>(o.size.z());
  const float z0 = -1.5f;
  const float refl = static_cast<float>(rng.uniform(0.25, 0.7));
  // Sides, back and roof.
  mesh.add_quad(f(-hx, hy, z0), f(hx, hy, z0), f(hx, hy, h), f(-hx, hy, h), Material::kWall, refl);
  mesh.add_quad(f(-hx, -hy, z0), f(-hx, hy, z0), f(-hx, hy, h), f(-hx, -hy, h), Material::kWall,
                refl);
  mesh.add_quad(f(hx, -hy, z0), f(hx, hy, z0), f(hx, hy, h), f(hx, -hy, h), Material::kWall, refl);
  mesh.add_quad(f(-hx, -hy, h), f(hx, -hy, h), f(hx, hy, h), f(-hx, hy, h), Material::kConcrete,
                0.2f);
  // Side walls get a few windows too (seen through gaps).
  building_facade(f, hx, hy, z0, h, rng, mesh, refl);
  // Entrance recess with a canopy on some buildings.
  if (rng.chance(0.4)) {
    const float x = static_cast<float>(rng.uniform(-hx + 2.0, hx - 2.0));
    local_box(f, V3(x - 1.2f, -hy - 1.2f, 2.6f), V3(x + 1.2f, -hy, 2.8f), mesh, Material::kMetal,
              0.45f);
  }
}

void build_house(const WorldObject& o, Rng& rng, TriangleMesh& mesh) {
  const Frame f = frame_of(o);
  const float hx = 0.5f * static_cast<float>(o.size.x()),
              hy = 0.5f * static_cast<float>(o.size.y());
  const float h = static_cast<float>(o.size.z());
  const float ridge = h + static_cast<float>(rng.uniform(1.5, 3.5));
  const float refl = static_cast<float>(rng.uniform(0.3, 0.7));
  const float z0 = -1.0f;
  mesh.add_quad(f(-hx, hy, z0), f(hx, hy, z0), f(hx, hy, h), f(-hx, hy, h), Material::kWall, refl);
  mesh.add_quad(f(-hx, -hy, z0), f(-hx, hy, z0), f(-hx, hy, h), f(-hx, -hy, h), Material::kWall,
                refl);
  mesh.add_quad(f(hx, -hy, z0), f(hx, hy, z0), f(hx, hy, h), f(hx, -hy, h), Material::kWall, refl);
  building_facade(f, hx, hy, z0, h, rng, mesh, refl);
  // Pitched roof with overhang; ridge along x.
  const float ov = 0.5f;
  const float rr = static_cast<float>(rng.uniform(0.1, 0.3));
  mesh.add_quad(f(-hx - ov, -hy - ov, h - 0.3f), f(hx + ov, -hy - ov, h - 0.3f),
                f(hx + ov, 0, ridge), f(-hx - ov, 0, ridge), Material::kConcrete, rr);
  mesh.add_quad(f(-hx - ov, hy + ov, h - 0.3f), f(hx + ov, hy + ov, h - 0.3f), f(hx + ov, 0, ridge),
                f(-hx - ov, 0, ridge), Material::kConcrete, rr);
  mesh.add_triangle(f(-hx, -hy, h), f(-hx, hy, h), f(-hx, 0, ridge), Material::kWall, refl);
  mesh.add_triangle(f(hx, -hy, h), f(hx, hy, h), f(hx, 0, ridge), Material::kWall, refl);
  if (rng.chance(0.5)) {  // chimney
    local_box(f, V3(hx * 0.4f, 0.5f, h), V3(hx * 0.4f + 0.6f, 1.1f, ridge + 0.8f), mesh,
              Material::kConcrete, 0.3f);
  }
}

void build_tree(const WorldObject& o, Rng& rng, TriangleMesh& mesh) {
  const Frame f = frame_of(o);
  const float r = 0.5f * static_cast<float>(o.size.x());
  const float H = static_cast<float>(o.size.z());
  const float rz = std::min(r * static_cast<float>(rng.uniform(0.8, 1.3)), 0.45f * H);
  const float trunk_h = H - 1.6f * rz;
  const float trunk_r = static_cast<float>(rng.uniform(0.12, 0.3));
  // Slightly leaning trunk made of two cylinders.
  const V3 base = f(0, 0, -0.3f);
  mesh.add_cylinder(base, trunk_r, trunk_h * 0.55f + 0.3f, 7, Material::kBark, 0.3f);
  const V3 lean(static_cast<float>(rng.uniform(-0.15, 0.15)),
                static_cast<float>(rng.uniform(-0.15, 0.15)), 0.0f);
  mesh.add_cylinder(base + lean + V3(0, 0, trunk_h * 0.55f + 0.3f), trunk_r * 0.8f,
                    trunk_h * 0.5f + rz, 6, Material::kBark, 0.3f);
  // Branches.
  const int branches = rng.uniform_int(3, 6);
  for (int i = 0; i < branches; ++i) {
    const float a = static_cast<float>(rng.uniform(0, 2 * M_PI));
    const float len = r * static_cast<float>(rng.uniform(0.5, 0.9));
    const float z = trunk_h + static_cast<float>(rng.uniform(-0.3, 0.6)) * rz;
    Eigen::Isometry3f p = f.pose;
    p.translate(V3(0.5f * len * std::cos(a), 0.5f * len * std::sin(a), z));
    p.rotate(Eigen::AngleAxisf(a, V3::UnitZ()));
    p.rotate(Eigen::AngleAxisf(-0.4f, V3::UnitY()));
    mesh.add_box(p, V3(len, 0.12f, 0.12f), Material::kBark, 0.3f);
  }
  // Crown: one to three overlapping lobes of foliage clutter.
  const int lobes = rng.uniform_int(1, 3);
  for (int l = 0; l < lobes; ++l) {
    const float s = l == 0 ? 1.0f : static_cast<float>(rng.uniform(0.5, 0.8));
    const V3 c(static_cast<float>(rng.uniform(-0.3, 0.3)) * r * (l > 0),
               static_cast<float>(rng.uniform(-0.3, 0.3)) * r * (l > 0), H - rz);
    const V3 radii(r * s, r * s * static_cast<float>(rng.uniform(0.8, 1.2)), rz * s);
    const double area =
        4.0 * M_PI * (radii.x() * radii.y() + radii.x() * radii.z() + radii.y() * radii.z()) / 3.0;
    clutter_ellipsoid(f, c, radii, clutter_count(area, 0.12, 1.1), 0.25f, 0.6f, rng, mesh,
                      Material::kFoliage, 0.5f);
  }
}

void build_bush(const WorldObject& o, Rng& rng, TriangleMesh& mesh) {
  const Frame f = frame_of(o);
  const V3 r(0.5f * static_cast<float>(o.size.x()), 0.5f * static_cast<float>(o.size.y()),
             0.5f * static_cast<float>(o.size.z()));
  const double area = 4.0 * M_PI * (r.x() * r.y() + r.x() * r.z() + r.y() * r.z()) / 3.0;
  clutter_ellipsoid(f, V3(0, 0, r.z() * 0.8f), r, clutter_count(area, 0.03, 1.3), 0.12f, 0.35f, rng,
                    mesh, Material::kFoliage, 0.45f);
}

void build_hedge(const WorldObject& o, Rng& rng, TriangleMesh& mesh) {
  const Frame f = frame_of(o);
  const V3 h(0.5f * static_cast<float>(o.size.x()), 0.5f * static_cast<float>(o.size.y()),
             static_cast<float>(o.size.z()));
  const double area = 2.0 * (4 * h.x() * h.z() + 2 * h.y() * h.z() + 4 * h.x() * h.y());
  clutter_box(f, V3(-h.x(), -h.y(), -0.1f), V3(h.x(), h.y(), h.z()), clutter_count(area, 0.03, 1.2),
              0.12f, 0.3f, rng, mesh, Material::kFoliage, 0.45f);
}

void build_pole(const WorldObject& o, Rng& rng, TriangleMesh& mesh) {
  const Frame f = frame_of(o);
  const float H = static_cast<float>(o.size.z());
  const float r = static_cast<float>(rng.uniform(0.07, 0.14));
  mesh.add_cylinder(f(0, 0, -0.3f), r, H + 0.3f, 8, Material::kMetal, 0.5f);
  const float arm = static_cast<float>(rng.uniform(1.0, 2.5));
  local_box(f, V3(-0.05f, -arm, H - 0.15f), V3(0.05f, 0, H - 0.05f), mesh, Material::kMetal, 0.5f);
  local_box(f, V3(-0.25f, -arm - 0.3f, H - 0.35f), V3(0.25f, -arm + 0.3f, H - 0.1f), mesh,
            Material::kMetal, 0.6f);
  if (rng.chance(0.3)) {  // a sign on the pole
    local_box(f, V3(-0.35f, -r - 0.05f, 2.2f), V3(0.35f, -r, 2.9f), mesh, Material::kSign, 0.9f);
  }
}

void build_sign(const WorldObject& o, Rng& rng, TriangleMesh& mesh) {
  const Frame f = frame_of(o);
  const float H = static_cast<float>(o.size.z());
  mesh.add_cylinder(f(0, 0, -0.3f), 0.04f, H + 0.3f, 6, Material::kMetal, 0.5f);
  const float w = static_cast<float>(o.size.x());
  const float ph = static_cast<float>(rng.uniform(0.5, 1.2)) * w;
  local_box(f, V3(-0.5f * w, -0.08f, H - ph), V3(0.5f * w, -0.05f, H), mesh, Material::kSign,
            static_cast<float>(rng.uniform(0.8, 1.0)));
}

void build_car(const WorldObject& o, Rng& rng, TriangleMesh& mesh) {
  const Frame f = frame_of(o);
  const float hl = 0.5f * static_cast<float>(o.size.x()),
              hw = 0.5f * static_cast<float>(o.size.y());
  const float h = static_cast<float>(o.size.z());
  const float paint = static_cast<float>(rng.uniform(0.05, 0.8));
  const float body_b = 0.3f, body_t = 0.3f + 0.45f * h;
  // Body with slightly rounded (tapered) ends.
  const V3 body[8] = {V3(-hl, -hw, body_b),
                      V3(hl, -hw, body_b),
                      V3(hl, hw, body_b),
                      V3(-hl, hw, body_b),
                      V3(-hl + 0.15f, -hw + 0.05f, body_t),
                      V3(hl - 0.3f, -hw + 0.05f, body_t),
                      V3(hl - 0.3f, hw - 0.05f, body_t),
                      V3(-hl + 0.15f, hw - 0.05f, body_t)};
  local_hexahedron(f, body, mesh, Material::kCarPaint, Material::kCarPaint, paint);
  // Tapered cabin (windshield and rear window slanted), glass sides.
  const float cf = hl * static_cast<float>(rng.uniform(0.1, 0.3));
  const float cb = -hl * static_cast<float>(rng.uniform(0.6, 0.85));
  const V3 cabin[8] = {V3(cb, -hw + 0.08f, body_t),       V3(cf + 0.6f, -hw + 0.08f, body_t),
                       V3(cf + 0.6f, hw - 0.08f, body_t), V3(cb, hw - 0.08f, body_t),
                       V3(cb + 0.4f, -hw + 0.2f, h),      V3(cf - 0.3f, -hw + 0.2f, h),
                       V3(cf - 0.3f, hw - 0.2f, h),       V3(cb + 0.4f, hw - 0.2f, h)};
  local_hexahedron(f, cabin, mesh, Material::kCarGlass, Material::kCarPaint, paint);
  // Wheels and the dark underside gap.
  for (int i = 0; i < 4; ++i) {
    const float x = (i & 1) ? hl - 0.75f : -hl + 0.75f;
    const float y = (i & 2) ? hw - 0.13f : -hw + 0.13f;
    local_box(f, V3(x - 0.32f, y - 0.12f, 0.0f), V3(x + 0.32f, y + 0.12f, 0.64f), mesh,
              Material::kCarPaint, 0.05f);
  }
  // Side mirrors.
  local_box(f, V3(cf + 0.3f, -hw - 0.15f, body_t), V3(cf + 0.45f, -hw, body_t + 0.15f), mesh,
            Material::kCarPaint, paint);
  local_box(f, V3(cf + 0.3f, hw, body_t), V3(cf + 0.45f, hw + 0.15f, body_t + 0.15f), mesh,
            Material::kCarPaint, paint);
}

void build_guard_rail(const WorldObject& o, Rng& rng, TriangleMesh& mesh) {
  const Frame f = frame_of(o);
  const float hl = 0.5f * static_cast<float>(o.size.x());
  local_box(f, V3(-hl, -0.05f, 0.45f), V3(hl, 0.0f, 0.8f), mesh, Material::kMetal,
            static_cast<float>(rng.uniform(0.5, 0.7)));
  for (float x = -hl + 0.5f; x < hl; x += 2.0f) {
    local_box(f, V3(x - 0.06f, 0.0f, -0.3f), V3(x + 0.06f, 0.12f, 0.75f), mesh, Material::kMetal,
              0.4f);
  }
}

void build_wall(const WorldObject& o, Rng& rng, TriangleMesh& mesh) {
  const Frame f = frame_of(o);
  const float hl = 0.5f * static_cast<float>(o.size.x()),
              hd = 0.5f * static_cast<float>(o.size.y());
  const float h = static_cast<float>(o.size.z());
  const float refl = static_cast<float>(rng.uniform(0.2, 0.5));
  // Segments of varying height (irregular top).
  const int n = std::max(1, static_cast<int>(2 * hl / 2.0f));
  const float seg = 2 * hl / n;
  for (int i = 0; i < n; ++i) {
    const float x0 = -hl + i * seg;
    const float hi = h * static_cast<float>(rng.uniform(0.85, 1.15));
    local_box(f, V3(x0, -hd, -0.3f), V3(x0 + seg, hd, hi), mesh, Material::kConcrete, refl);
  }
}

}  // namespace

void build_object_mesh(const WorldObject& object, TriangleMesh& mesh) {
  Rng rng(object.seed);
  switch (object.kind) {
    case ObjectKind::kBuilding:
      build_building(object, rng, mesh);
      break;
    case ObjectKind::kHouse:
      build_house(object, rng, mesh);
      break;
    case ObjectKind::kTree:
      build_tree(object, rng, mesh);
      break;
    case ObjectKind::kBush:
      build_bush(object, rng, mesh);
      break;
    case ObjectKind::kHedge:
      build_hedge(object, rng, mesh);
      break;
    case ObjectKind::kPole:
      build_pole(object, rng, mesh);
      break;
    case ObjectKind::kSign:
      build_sign(object, rng, mesh);
      break;
    case ObjectKind::kCar:
      build_car(object, rng, mesh);
      break;
    case ObjectKind::kGuardRail:
      build_guard_rail(object, rng, mesh);
      break;
    case ObjectKind::kWall:
      build_wall(object, rng, mesh);
      break;
  }
}

const char* object_kind_name(ObjectKind kind) {
  switch (kind) {
    case ObjectKind::kBuilding:
      return "building";
    case ObjectKind::kHouse:
      return "house";
    case ObjectKind::kTree:
      return "tree";
    case ObjectKind::kBush:
      return "bush";
    case ObjectKind::kHedge:
      return "hedge";
    case ObjectKind::kPole:
      return "pole";
    case ObjectKind::kSign:
      return "sign";
    case ObjectKind::kCar:
      return "car";
    case ObjectKind::kGuardRail:
      return "guard_rail";
    case ObjectKind::kWall:
      return "wall";
  }
  return "unknown";
}

}  // namespace litamin2::sim

#include "litamin2/sim/world.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>

#include "litamin2/sim/random.hpp"

namespace litamin2::sim {
namespace {

constexpr double kSampleSpacing = 2.0;  // metres between path samples
constexpr double kCell = 8.0;           // path index cell
constexpr double kLattice = 4.0;        // base-height lattice spacing

std::int64_t pack(int x, int y) {
  return (static_cast<std::int64_t>(x) << 32) ^ static_cast<std::uint32_t>(y);
}

double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

struct PathSample {
  Eigen::Vector3d p;
  Eigen::Vector2d t;  // unit heading
  double speed = 0.0;
  double arc = 0.0;
  int path = 0;
  int next = -1;  // next sample of the same path
  District district = District::kUrban;
};

/// Oriented rectangle footprint.
struct Footprint {
  Eigen::Vector2d c;
  double yaw;
  double hx, hy;
};

}  // namespace

WorldOptions WorldOptions::ground_only() {
  WorldOptions o;
  o.ground_roughness = 0.0;
  o.terrain_amplitude = 0.0;
  o.kerb_height = 0.0;
  o.density = 0.0;
  o.buildings = o.vegetation = o.street_furniture = o.parked_cars = false;
  return o;
}

struct World::Impl {
  WorldOptions opt;
  std::uint64_t seed = 0;
  std::vector<PathSample> samples;
  std::vector<std::vector<int>> path_samples;  // sample indices per path, in order
  std::unordered_map<std::int64_t, std::vector<int>> grid;
  double max_segment = kSampleSpacing;
  std::vector<WorldObject> objects;
  std::unordered_map<std::int64_t, std::vector<std::uint32_t>> tile_objects;
  std::unordered_set<std::int64_t> tiles;
  std::unordered_set<std::int64_t> occupied;  // 1 m cells, layout only
  double max_radius = 0.0;

  // ---- path queries ------------------------------------------------------------------------

  /// Nearest path segment within max_d: (distance, sample index or -1).
  std::pair<double, int> nearest(double x, double y, double max_d) const {
    const double reach = max_d + max_segment;
    const int cx0 = static_cast<int>(std::floor((x - reach) / kCell));
    const int cx1 = static_cast<int>(std::floor((x + reach) / kCell));
    const int cy0 = static_cast<int>(std::floor((y - reach) / kCell));
    const int cy1 = static_cast<int>(std::floor((y + reach) / kCell));
    double best = max_d * max_d;
    int best_i = -1;
    const Eigen::Vector2d q(x, y);
    for (int cx = cx0; cx <= cx1; ++cx) {
      for (int cy = cy0; cy <= cy1; ++cy) {
        const auto it = grid.find(pack(cx, cy));
        if (it == grid.end()) continue;
        for (int i : it->second) {
          const PathSample& s = samples[i];
          const Eigen::Vector2d a = s.p.head<2>();
          double d2;
          if (s.next >= 0) {
            const Eigen::Vector2d b = samples[s.next].p.head<2>();
            const Eigen::Vector2d ab = b - a;
            const double l2 = ab.squaredNorm();
            const double t = l2 > 1e-12 ? std::clamp((q - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
            d2 = (a + t * ab - q).squaredNorm();
          } else {
            d2 = (a - q).squaredNorm();
          }
          if (d2 < best) {
            best = d2;
            best_i = i;
          }
        }
      }
    }
    return {best_i >= 0 ? std::sqrt(best) : max_d, best_i};
  }

  /// Road height (sensor height below the trajectories): a Gaussian-weighted local plane fit
  /// over nearby samples (ridge-regularised slopes, so it is exact on a path's own slope and
  /// flat across a straight road, also at the ends of a trajectory).
  double road_height_raw(double x, double y) const {
    constexpr double kSigma = 10.0, kRadius = 30.0;
    const int cx0 = static_cast<int>(std::floor((x - kRadius) / kCell));
    const int cx1 = static_cast<int>(std::floor((x + kRadius) / kCell));
    const int cy0 = static_cast<int>(std::floor((y - kRadius) / kCell));
    const int cy1 = static_cast<int>(std::floor((y + kRadius) / kCell));
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
    double wsum = 0.0;
    for (int cx = cx0; cx <= cx1; ++cx) {
      for (int cy = cy0; cy <= cy1; ++cy) {
        const auto it = grid.find(pack(cx, cy));
        if (it == grid.end()) continue;
        for (int i : it->second) {
          const Eigen::Vector2d dxy = samples[i].p.head<2>() - Eigen::Vector2d(x, y);
          const double d2 = dxy.squaredNorm();
          if (d2 > kRadius * kRadius) continue;
          const double w = std::exp(-0.5 * d2 / (kSigma * kSigma));
          const Eigen::Vector3d u(1.0, dxy.x(), dxy.y());
          A += w * u * u.transpose();
          rhs += w * samples[i].p.z() * u;
          wsum += w;
        }
      }
    }
    if (wsum > 1e-9) {
      A(1, 1) += 4.0 * wsum;
      A(2, 2) += 4.0 * wsum;
      return A.ldlt().solve(rhs)(0) - opt.sensor_height;
    }
    // Far from every path: the nearest sample's height.
    const auto [d, i] = nearest(x, y, opt.corridor_radius + 4.0 * opt.tile_size);
    (void)d;
    if (i >= 0) return samples[i].p.z() - opt.sensor_height;
    return samples.empty() ? -opt.sensor_height : samples.front().p.z() - opt.sensor_height;
  }

  /// Bilinear interpolation of road_height_raw on a kLattice grid (smooth and cheap).
  double road_height(double x, double y) const {
    const double gx = x / kLattice, gy = y / kLattice;
    const double fx = std::floor(gx), fy = std::floor(gy);
    const double tx = gx - fx, ty = gy - fy;
    const double h00 = road_height_raw(fx * kLattice, fy * kLattice);
    const double h10 = road_height_raw((fx + 1) * kLattice, fy * kLattice);
    const double h01 = road_height_raw(fx * kLattice, (fy + 1) * kLattice);
    const double h11 = road_height_raw((fx + 1) * kLattice, (fy + 1) * kLattice);
    return (1 - ty) * ((1 - tx) * h00 + tx * h10) + ty * ((1 - tx) * h01 + tx * h11);
  }

  /// Smooth value noise in [-1, 1] with unit lattice.
  double value_noise(double x, double y, std::uint64_t salt) const {
    const double fx = std::floor(x), fy = std::floor(y);
    const double tx = smoothstep(0, 1, x - fx), ty = smoothstep(0, 1, y - fy);
    auto at = [&](double ix, double iy) {
      const std::uint64_t h =
          hash_combine(hash_combine(hash_combine(seed, salt),
                                    static_cast<std::uint64_t>(static_cast<std::int64_t>(ix))),
                       static_cast<std::uint64_t>(static_cast<std::int64_t>(iy)));
      return static_cast<double>(h >> 11) * 0x1.0p-52 - 1.0;
    };
    return (1 - ty) * ((1 - tx) * at(fx, fy) + tx * at(fx + 1, fy)) +
           ty * ((1 - tx) * at(fx, fy + 1) + tx * at(fx + 1, fy + 1));
  }

  /// Ground height given the distance to the path and the district (shared by ground_height
  /// and the tile builder so both agree).
  double ground_at(double x, double y, double base, double d, District district) const {
    double z = base;
    const bool open = district == District::kOpen;
    const double road = open ? opt.road_half_width + 3.0 : opt.road_half_width;
    // Terrain: hills and embankments away from the road.
    const double amp = opt.terrain_amplitude * (open ? 1.6 : 1.0);
    if (amp > 0) {
      const double t =
          0.6 * value_noise(x / 23.0, y / 23.0, 11) + value_noise(x / 71.0, y / 71.0, 12);
      z += amp * t * smoothstep(road + 3.0, road + 30.0, d);
    }
    // Gentle undulation everywhere, small on the road.
    if (opt.ground_roughness > 0) {
      z += 2.5 * opt.ground_roughness * value_noise(x / 7.0, y / 7.0, 13) * (d < road ? 0.5 : 1.0);
    }
    if (!open && district != District::kGreen) {
      z += opt.kerb_height * smoothstep(road, road + 0.25, d);
    }
    return z;
  }

  District district_near(double x, double y) const {
    const auto [d, i] = nearest(x, y, 200.0);
    (void)d;
    return i >= 0 ? samples[i].district : District::kUrban;
  }

  // ---- construction ------------------------------------------------------------------------

  void add_samples(const std::vector<std::vector<Eigen::Isometry3d>>& paths) {
    for (std::size_t p = 0; p < paths.size(); ++p) {
      const auto& poses = paths[p];
      std::vector<int> idx;
      double since = 0.0, arc = 0.0;
      for (std::size_t k = 0; k < poses.size(); ++k) {
        if (k > 0) {
          const double step = (poses[k].translation() - poses[k - 1].translation()).norm();
          since += step;
          arc += step;
        }
        if (k != 0 && since < kSampleSpacing && k + 1 != poses.size()) continue;
        if (k != 0 && since < 1e-3) continue;
        since = 0.0;
        PathSample s;
        s.p = poses[k].translation();
        Eigen::Vector2d h = poses[k].linear().col(0).head<2>();
        s.t = h.norm() > 1e-6 ? h.normalized() : Eigen::Vector2d(1, 0);
        // Speed over +-10 frames at 10 Hz.
        const std::size_t k0 = k >= 10 ? k - 10 : 0, k1 = std::min(poses.size() - 1, k + 10);
        double dist = 0.0;
        for (std::size_t j = k0; j < k1; ++j) {
          dist += (poses[j + 1].translation() - poses[j].translation()).norm();
        }
        s.speed = k1 > k0 ? dist / (0.1 * static_cast<double>(k1 - k0)) : 0.0;
        s.arc = arc;
        s.path = static_cast<int>(p);
        if (!idx.empty()) {
          samples[idx.back()].next = static_cast<int>(samples.size());
          max_segment = std::max(max_segment, (s.p - samples[idx.back()].p).head<2>().norm());
        }
        idx.push_back(static_cast<int>(samples.size()));
        samples.push_back(s);
      }
      path_samples.push_back(std::move(idx));
    }
    for (std::size_t i = 0; i < samples.size(); ++i) {
      const auto& p = samples[i].p;
      grid[pack(static_cast<int>(std::floor(p.x() / kCell)),
                static_cast<int>(std::floor(p.y() / kCell)))]
          .push_back(static_cast<int>(i));
    }
  }

  void assign_districts() {
    for (std::size_t p = 0; p < path_samples.size(); ++p) {
      Rng rng(hash_combine(hash_combine(seed, 0xd157), p));
      double block_end = -1.0;
      District current = District::kUrban;
      for (int i : path_samples[p]) {
        PathSample& s = samples[i];
        if (s.arc >= block_end) {
          block_end = s.arc + rng.uniform(60.0, 180.0);
          const auto& w = opt.district_weights;
          const double r = rng.uniform() * std::max(1e-12, w[0] + w[1] + w[2]);
          current = r < w[0]          ? District::kUrban
                    : r < w[0] + w[1] ? District::kSuburban
                                      : District::kGreen;
        }
        s.district = s.speed > opt.open_speed ? District::kOpen : current;
      }
    }
  }

  void mark_tiles() {
    const double T = opt.tile_size, R = opt.corridor_radius;
    Eigen::Vector2d last(std::numeric_limits<double>::infinity(), 0);
    for (const auto& s : samples) {
      if ((s.p.head<2>() - last).norm() < 5.0) continue;
      last = s.p.head<2>();
      const int x0 = static_cast<int>(std::floor((last.x() - R) / T));
      const int x1 = static_cast<int>(std::floor((last.x() + R) / T));
      const int y0 = static_cast<int>(std::floor((last.y() - R) / T));
      const int y1 = static_cast<int>(std::floor((last.y() + R) / T));
      for (int x = x0; x <= x1; ++x) {
        for (int y = y0; y <= y1; ++y) {
          const double dx = std::max({x * T - last.x(), 0.0, last.x() - (x + 1) * T});
          const double dy = std::max({y * T - last.y(), 0.0, last.y() - (y + 1) * T});
          if (dx * dx + dy * dy <= R * R) tiles.insert(pack(x, y));
        }
      }
    }
  }

  /// Point at arc length `a` of path p: (position, unit heading, district).
  bool at_arc(int p, double a, Eigen::Vector2d& pos, Eigen::Vector2d& tan, District& dist) const {
    const auto& idx = path_samples[p];
    if (idx.empty()) return false;
    const double first = samples[idx.front()].arc, last = samples[idx.back()].arc;
    if (a < first || a > last) return false;
    auto it = std::lower_bound(idx.begin(), idx.end(), a,
                               [&](int i, double v) { return samples[i].arc < v; });
    if (it == idx.end()) --it;
    const int j = *it;
    const int i = it == idx.begin() ? j : *(it - 1);
    const double a0 = samples[i].arc, a1 = samples[j].arc;
    const double t = a1 > a0 ? (a - a0) / (a1 - a0) : 0.0;
    pos = (1 - t) * samples[i].p.head<2>() + t * samples[j].p.head<2>();
    const Eigen::Vector2d d = samples[j].p.head<2>() - samples[i].p.head<2>();
    tan = d.norm() > 1e-6 ? d.normalized() : samples[j].t;
    dist = samples[t < 0.5 ? i : j].district;
    return true;
  }

  /// True if the footprint keeps `clearance` from every path and is free in the layout.
  bool footprint_free(const Footprint& f, double clearance) const {
    const Eigen::Vector2d ex(std::cos(f.yaw), std::sin(f.yaw)), ey(-ex.y(), ex.x());
    const int nx = std::max(1, static_cast<int>(std::ceil(2 * f.hx))),
              ny = std::max(1, static_cast<int>(std::ceil(2 * f.hy)));
    // Boundary against the paths.
    for (int i = 0; i <= nx; ++i) {
      for (int j = 0; j <= ny; ++j) {
        if (i != 0 && i != nx && j != 0 && j != ny) continue;
        const Eigen::Vector2d q =
            f.c + ex * (-f.hx + 2 * f.hx * i / nx) + ey * (-f.hy + 2 * f.hy * j / ny);
        if (nearest(q.x(), q.y(), clearance).second >= 0) return false;
      }
    }
    // Interior against other objects.
    for (int i = 0; i <= nx; ++i) {
      for (int j = 0; j <= ny; ++j) {
        const Eigen::Vector2d q =
            f.c + ex * (-f.hx + 2 * f.hx * i / nx) + ey * (-f.hy + 2 * f.hy * j / ny);
        if (occupied.count(
                pack(static_cast<int>(std::floor(q.x())), static_cast<int>(std::floor(q.y())))))
          return false;
      }
    }
    return true;
  }

  void occupy(const Footprint& f) {
    const Eigen::Vector2d ex(std::cos(f.yaw), std::sin(f.yaw)), ey(-ex.y(), ex.x());
    const int nx = std::max(1, static_cast<int>(std::ceil(2 * f.hx))),
              ny = std::max(1, static_cast<int>(std::ceil(2 * f.hy)));
    for (int i = 0; i <= nx; ++i) {
      for (int j = 0; j <= ny; ++j) {
        const Eigen::Vector2d q =
            f.c + ex * (-f.hx + 2 * f.hx * i / nx) + ey * (-f.hy + 2 * f.hy * j / ny);
        occupied.insert(
            pack(static_cast<int>(std::floor(q.x())), static_cast<int>(std::floor(q.y()))));
      }
    }
  }

  /// Places an object of footprint half-sizes (hx, hy) at arc a of path p, `lateral` metres to
  /// side `side` (+1 left, -1 right), front facing the road. Returns false if rejected.
  bool place(int p, int side, double a, double lateral, ObjectKind kind,
             const Eigen::Vector3d& size, double foot_hx, double foot_hy, double clearance,
             Rng& rng) {
    Eigen::Vector2d pos, tan;
    District dist;
    if (!at_arc(p, a, pos, tan, dist)) return false;
    const Eigen::Vector2d n(-tan.y(), tan.x());
    Footprint f;
    f.c = pos + side * lateral * n;
    const double heading = std::atan2(tan.y(), tan.x());
    f.yaw = side > 0 ? heading : heading + M_PI;
    if (kind == ObjectKind::kTree || kind == ObjectKind::kBush) f.yaw = rng.uniform(0, 2 * M_PI);
    if (kind == ObjectKind::kCar)
      f.yaw += rng.uniform(-0.04, 0.04) + (rng.chance(0.5) ? M_PI : 0.0);
    f.hx = foot_hx;
    f.hy = foot_hy;
    if (!footprint_free(f, clearance)) return false;
    occupy(f);
    WorldObject o;
    o.kind = kind;
    o.center = f.c;
    o.yaw = f.yaw;
    o.size = size;
    o.seed = rng.next();
    const auto [d, _] = nearest(f.c.x(), f.c.y(), 200.0);
    (void)_;
    o.ground_z = ground_at(f.c.x(), f.c.y(), road_height(f.c.x(), f.c.y()), d, dist);
    if (kind == ObjectKind::kBuilding || kind == ObjectKind::kHouse || kind == ObjectKind::kWall) {
      // Sink to the lowest ground under the footprint so no gap shows on slopes.
      const Eigen::Vector2d ex(std::cos(f.yaw), std::sin(f.yaw)), ey(-ex.y(), ex.x());
      for (int sx = -1; sx <= 1; sx += 2) {
        for (int sy = -1; sy <= 1; sy += 2) {
          const Eigen::Vector2d q = f.c + sx * f.hx * ex + sy * f.hy * ey;
          const auto [dq, iq] = nearest(q.x(), q.y(), 200.0);
          (void)iq;
          o.ground_z =
              std::min(o.ground_z, ground_at(q.x(), q.y(), road_height(q.x(), q.y()), dq, dist));
        }
      }
    }
    const double radius = std::hypot(size.x(), size.y()) * 0.5 + 3.0;
    max_radius = std::max(max_radius, radius);
    const int tx = static_cast<int>(std::floor(f.c.x() / opt.tile_size));
    const int ty = static_cast<int>(std::floor(f.c.y() / opt.tile_size));
    tile_objects[pack(tx, ty)].push_back(static_cast<std::uint32_t>(objects.size()));
    tiles.insert(pack(tx, ty));
    objects.push_back(o);
    return true;
  }

  double density_chance(double p) const { return std::min(1.0, p * opt.density); }

  void layout_frontage(int p, int side, Rng& rng) {
    const auto& idx = path_samples[p];
    if (idx.size() < 2) return;
    const double L = samples[idx.back()].arc, A0 = samples[idx.front()].arc;
    const double hw = opt.road_half_width;
    double a = A0 - 10.0;
    while (a < L + 10.0) {
      Eigen::Vector2d pos, tan;
      District d = District::kUrban;
      if (!at_arc(p, std::clamp(a, A0, L), pos, tan, d)) break;
      switch (d) {
        case District::kUrban: {
          const double w = rng.uniform(10.0, 28.0), depth = rng.uniform(10.0, 18.0);
          const double h = rng.uniform(8.0, 22.0), setback = rng.uniform(hw + 2.0, hw + 6.0);
          bool ok = opt.buildings && rng.chance(density_chance(0.9)) &&
                    place(p, side, a + 0.5 * w, setback + 0.5 * depth, ObjectKind::kBuilding,
                          {w, depth, h}, 0.5 * w, 0.5 * depth, hw + 1.5, rng);
          if (!ok && opt.buildings) {  // narrower retry (curves)
            ok = place(p, side, a + 0.25 * w, setback + 0.5 * depth + 2.0, ObjectKind::kBuilding,
                       {0.5 * w, depth, h}, 0.25 * w, 0.5 * depth, hw + 1.5, rng);
          }
          a += (ok ? w : 4.0) + (rng.chance(0.3) ? rng.uniform(3.0, 14.0) : rng.uniform(0.0, 0.5));
          break;
        }
        case District::kSuburban: {
          const double w = rng.uniform(8.0, 14.0), depth = rng.uniform(8.0, 12.0);
          const double h = rng.uniform(3.0, 6.5), setback = rng.uniform(hw + 5.0, hw + 14.0);
          const bool ok = opt.buildings && rng.chance(density_chance(0.75)) &&
                          place(p, side, a + 0.5 * w, setback + 0.5 * depth, ObjectKind::kHouse,
                                {w, depth, h}, 0.5 * w + 0.5, 0.5 * depth + 0.5, hw + 1.5, rng);
          if (ok && opt.vegetation && rng.chance(density_chance(0.5))) {
            const double hl = rng.uniform(0.8, 1.5), hh = rng.uniform(0.8, 1.9);
            place(p, side, a + 0.5 * w, hw + rng.uniform(2.0, 3.5), ObjectKind::kHedge, {w, hl, hh},
                  0.5 * w, 0.5 * hl, hw + 1.0, rng);
          } else if (ok && opt.street_furniture && rng.chance(density_chance(0.3))) {
            const double th = rng.uniform(0.2, 0.35), hh = rng.uniform(0.5, 1.8);
            place(p, side, a + 0.5 * w, hw + rng.uniform(2.0, 3.5), ObjectKind::kWall, {w, th, hh},
                  0.5 * w, 0.5 * th, hw + 1.0, rng);
          }
          a += (ok ? w : 5.0) + rng.uniform(3.0, 16.0);
          break;
        }
        case District::kGreen: {
          if (opt.street_furniture && rng.chance(density_chance(0.15))) {
            const double w = rng.uniform(6.0, 20.0), th = rng.uniform(0.2, 0.4);
            place(p, side, a + 0.5 * w, hw + rng.uniform(3.0, 8.0), ObjectKind::kWall,
                  {w, th, rng.uniform(0.8, 2.5)}, 0.5 * w, 0.5 * th, hw + 1.0, rng);
            a += w;
          }
          a += rng.uniform(8.0, 30.0);
          break;
        }
        case District::kOpen: {
          if (opt.street_furniture && rng.chance(density_chance(0.8))) {
            place(p, side, a + 4.0, hw + 3.5, ObjectKind::kGuardRail, {8.0, 0.2, 0.8}, 4.0, 0.2,
                  hw + 2.5, rng);
          }
          a += 8.0;
          break;
        }
      }
    }
  }

  void layout_kerb(int p, int side, Rng& rng) {
    const auto& idx = path_samples[p];
    if (idx.size() < 2) return;
    const double L = samples[idx.back()].arc, A0 = samples[idx.front()].arc;
    const double hw = opt.road_half_width;
    double a = A0;
    double next_pole = A0 + rng.uniform(0.0, 30.0);
    while (a < L) {
      Eigen::Vector2d pos, tan;
      District d;
      if (!at_arc(p, a, pos, tan, d)) break;
      const bool open = d == District::kOpen;
      const double kerb = open ? hw + 3.5 : hw;
      // Lamps and signs.
      if (a >= next_pole) {
        if (opt.street_furniture && rng.chance(density_chance(open ? 0.3 : 0.8))) {
          place(p, side, a, kerb + rng.uniform(0.6, 1.5), ObjectKind::kPole,
                {0.3, 0.3, rng.uniform(5.5, 9.0)}, 0.3, 0.3, kerb + 0.3, rng);
        }
        next_pole = a + (open ? rng.uniform(60.0, 200.0) : rng.uniform(22.0, 40.0));
      }
      if (opt.street_furniture && rng.chance(density_chance(open ? 0.02 : 0.05))) {
        const double w = open ? rng.uniform(1.5, 4.0) : rng.uniform(0.5, 0.9);
        place(p, side, a + 1.0, kerb + rng.uniform(0.5, 1.5), ObjectKind::kSign,
              {w, 0.1, open ? rng.uniform(2.5, 5.0) : rng.uniform(2.2, 3.2)}, 0.5 * w, 0.3,
              kerb + 0.3, rng);
      }
      // Street trees.
      const double tree_p = d == District::kUrban      ? 0.45
                            : d == District::kSuburban ? 0.4
                            : d == District::kGreen    ? 0.85
                                                       : 0.05;
      if (opt.vegetation && rng.chance(density_chance(tree_p))) {
        const double r = rng.uniform(1.5, 3.5), h = rng.uniform(2.2 * r, 4.0 * r);
        place(p, side, a + rng.uniform(0.0, 3.0), kerb + rng.uniform(1.0, 3.0) + (open ? 6.0 : 0.0),
              ObjectKind::kTree, {2 * r, 2 * r, h}, 0.6, 0.6, kerb + 0.5, rng);
      }
      // Parked cars in runs.
      const double car_p = d == District::kUrban ? 0.55 : d == District::kSuburban ? 0.3 : 0.0;
      if (opt.parked_cars && rng.chance(density_chance(car_p))) {
        const int run = rng.uniform_int(1, d == District::kUrban ? 7 : 3);
        for (int c = 0; c < run && a < L; ++c) {
          const double len = rng.uniform(3.9, 4.9), wid = rng.uniform(1.7, 1.95);
          place(p, side, a + 0.5 * len, hw - 1.05, ObjectKind::kCar,
                {len, wid, rng.uniform(1.4, 1.65)}, 0.5 * len, 0.5 * wid, 3.4, rng);
          a += len + rng.uniform(0.7, 2.5);
        }
      }
      a += d == District::kOpen ? rng.uniform(15.0, 40.0) : rng.uniform(5.0, 12.0);
    }
  }

  void layout_scatter(int p, int side, Rng& rng) {
    const auto& idx = path_samples[p];
    if (idx.size() < 2) return;
    const double L = samples[idx.back()].arc, A0 = samples[idx.front()].arc;
    const double hw = opt.road_half_width;
    for (double a = A0; a < L; a += 5.0) {
      Eigen::Vector2d pos, tan;
      District d;
      if (!at_arc(p, a, pos, tan, d)) break;
      const double bush_p = d == District::kUrban      ? 0.15
                            : d == District::kSuburban ? 0.5
                            : d == District::kGreen    ? 0.9
                                                       : 0.15;
      const double tree_p = d == District::kUrban      ? 0.05
                            : d == District::kSuburban ? 0.3
                            : d == District::kGreen    ? 0.9
                                                       : 0.08;
      if (opt.vegetation && rng.chance(density_chance(bush_p))) {
        const double s = rng.uniform(0.6, 2.5);
        place(p, side, a + rng.uniform(0, 5), hw + rng.uniform(2.0, 25.0), ObjectKind::kBush,
              {s * rng.uniform(0.8, 1.6), s, s * rng.uniform(0.5, 1.0)}, 0.4 * s, 0.4 * s, hw + 0.8,
              rng);
      }
      if (opt.vegetation && rng.chance(density_chance(tree_p))) {
        const double r = rng.uniform(1.5, 4.0), h = rng.uniform(2.2 * r, 4.0 * r);
        place(p, side, a + rng.uniform(0, 5),
              hw + rng.uniform(d == District::kOpen ? 12.0 : 4.0, 30.0), ObjectKind::kTree,
              {2 * r, 2 * r, h}, 0.8, 0.8, hw + 1.0, rng);
      }
    }
  }
};

World::World(const std::vector<std::vector<Eigen::Isometry3d>>& sensor_paths, std::uint64_t seed,
             const WorldOptions& options)
    : impl_(std::make_unique<Impl>()) {
  if (options.tile_size <= 0 || options.ground_resolution <= 0) {
    throw std::invalid_argument("World: tile_size and ground_resolution must be positive");
  }
  impl_->opt = options;
  impl_->seed = seed;
  impl_->add_samples(sensor_paths);
  if (impl_->samples.empty()) throw std::invalid_argument("World: no trajectory poses given");
  impl_->assign_districts();
  impl_->mark_tiles();
  // Layers in a fixed order: frontage first (largest objects), then kerb items, then scatter.
  for (int layer = 0; layer < 3; ++layer) {
    for (std::size_t p = 0; p < impl_->path_samples.size(); ++p) {
      for (int side = -1; side <= 1; side += 2) {
        Rng rng(hash_combine(hash_combine(hash_combine(seed, layer), p), side + 7));
        if (layer == 0) impl_->layout_frontage(static_cast<int>(p), side, rng);
        if (layer == 1) impl_->layout_kerb(static_cast<int>(p), side, rng);
        if (layer == 2) impl_->layout_scatter(static_cast<int>(p), side, rng);
      }
    }
  }
  impl_->occupied.clear();
  impl_->occupied.rehash(0);
}

World::World(const std::vector<Eigen::Isometry3d>& sensor_path, std::uint64_t seed,
             const WorldOptions& options)
    : World(std::vector<std::vector<Eigen::Isometry3d>>{sensor_path}, seed, options) {}

World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

std::uint64_t World::seed() const {
  return impl_->seed;
}
const WorldOptions& World::options() const {
  return impl_->opt;
}
std::size_t World::tile_count() const {
  return impl_->tiles.size();
}
const std::vector<WorldObject>& World::objects() const {
  return impl_->objects;
}
double World::max_object_radius() const {
  return impl_->max_radius;
}

TileKey World::tile_of(const Eigen::Vector2d& xy) const {
  return {static_cast<int>(std::floor(xy.x() / impl_->opt.tile_size)),
          static_cast<int>(std::floor(xy.y() / impl_->opt.tile_size))};
}

std::vector<TileKey> World::tiles_near(const Eigen::Vector2d& xy, double radius) const {
  const double T = impl_->opt.tile_size;
  std::vector<TileKey> out;
  const int x0 = static_cast<int>(std::floor((xy.x() - radius) / T));
  const int x1 = static_cast<int>(std::floor((xy.x() + radius) / T));
  const int y0 = static_cast<int>(std::floor((xy.y() - radius) / T));
  const int y1 = static_cast<int>(std::floor((xy.y() + radius) / T));
  for (int x = x0; x <= x1; ++x) {
    for (int y = y0; y <= y1; ++y) {
      const double dx = std::max({x * T - xy.x(), 0.0, xy.x() - (x + 1) * T});
      const double dy = std::max({y * T - xy.y(), 0.0, xy.y() - (y + 1) * T});
      if (dx * dx + dy * dy <= radius * radius && impl_->tiles.count(pack(x, y))) {
        out.push_back({x, y});
      }
    }
  }
  return out;
}

double World::ground_height(double x, double y) const {
  const auto [d, i] = impl_->nearest(x, y, 200.0);
  const District district = i >= 0 ? impl_->samples[i].district : District::kUrban;
  return impl_->ground_at(x, y, impl_->road_height(x, y), d, district);
}

double World::distance_to_path(double x, double y, double max_distance) const {
  return impl_->nearest(x, y, max_distance).first;
}

District World::district_at(double x, double y) const {
  return impl_->district_near(x, y);
}

TriangleMesh World::build_tile(const TileKey& key) const {
  const Impl& m = *impl_;
  TriangleMesh mesh;
  if (!m.tiles.count(pack(key.x, key.y))) return mesh;
  const double T = m.opt.tile_size, r = m.opt.ground_resolution;
  const int n = std::max(1, static_cast<int>(std::round(T / r)));
  const double step = T / n;
  const double x0 = key.x * T, y0 = key.y * T;
  // Base height on the lattice covering the tile (+1 cell margin), then bilinear.
  const int l0x = static_cast<int>(std::floor(x0 / kLattice)),
            l0y = static_cast<int>(std::floor(y0 / kLattice));
  const int ln = static_cast<int>(std::ceil(T / kLattice)) + 2;
  std::vector<double> lattice(static_cast<std::size_t>(ln * ln));
  for (int i = 0; i < ln; ++i) {
    for (int j = 0; j < ln; ++j) {
      lattice[i * ln + j] = m.road_height_raw((l0x + i) * kLattice, (l0y + j) * kLattice);
    }
  }
  auto base_at = [&](double x, double y) {
    const double gx = x / kLattice - l0x, gy = y / kLattice - l0y;
    const int ix = std::clamp(static_cast<int>(std::floor(gx)), 0, ln - 2);
    const int iy = std::clamp(static_cast<int>(std::floor(gy)), 0, ln - 2);
    const double tx = gx - ix, ty = gy - iy;
    return (1 - ty) * ((1 - tx) * lattice[ix * ln + iy] + tx * lattice[(ix + 1) * ln + iy]) +
           ty * ((1 - tx) * lattice[ix * ln + iy + 1] + tx * lattice[(ix + 1) * ln + iy + 1]);
  };
  const int nv = n + 1;
  const District tile_district = m.district_near(x0 + 0.5 * T, y0 + 0.5 * T);
  std::vector<double> dist(static_cast<std::size_t>(nv * nv));
  std::vector<District> districts(dist.size());
  mesh.vertices.resize(dist.size());
  for (int i = 0; i < nv; ++i) {
    for (int j = 0; j < nv; ++j) {
      const double x = x0 + i * step, y = y0 + j * step;
      const auto [d, si] = m.nearest(x, y, 40.0);
      const District dd = si >= 0 ? m.samples[si].district : tile_district;
      double z = m.ground_at(x, y, base_at(x, y), d, dd);
      if (m.opt.ground_roughness > 0) {
        // Per-vertex roughness keyed by the global vertex index (seamless across tiles).
        const auto gx = static_cast<std::int64_t>(std::llround(x / step));
        const auto gy = static_cast<std::int64_t>(std::llround(y / step));
        Rng rng(hash_combine(hash_combine(hash_combine(m.seed, 0x6a0d), gx), gy));
        const double amp = d < m.opt.road_half_width ? 0.6 : 1.5;  // grass is rougher
        z += amp * m.opt.ground_roughness * (rng.uniform() + rng.uniform() + rng.uniform() - 1.5) *
             2.0;
      }
      dist[i * nv + j] = d;
      districts[i * nv + j] = dd;
      mesh.vertices[i * nv + j] =
          Eigen::Vector3f(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z));
    }
  }
  const double hw = m.opt.road_half_width;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const auto a = static_cast<std::uint32_t>(i * nv + j), b = a + nv, c = b + 1, d = a + 1;
      const double dc = 0.25 * (dist[a] + dist[b] + dist[c] + dist[d]);
      const District dd = districts[a];
      const double road = dd == District::kOpen ? hw + 3.0 : hw;
      Material mat = Material::kAsphalt;
      float refl = 0.12f;
      Rng rng(hash_combine(
          hash_combine(m.seed ^ 0x9e37, static_cast<std::uint64_t>(key.x * 100003 + i)),
          static_cast<std::uint64_t>(key.y * 100019 + j)));
      if (dc >= road) {
        if (dd != District::kOpen && dd != District::kGreen && dc < road + 3.0) {
          mat = Material::kSidewalk;
          refl = static_cast<float>(rng.uniform(0.2, 0.3));
        } else {
          mat = Material::kGrass;
          refl = static_cast<float>(rng.uniform(0.3, 0.55));
        }
      } else {
        refl = static_cast<float>(rng.uniform(0.09, 0.15));
        // Lane marking near the path centre line offset (dashed look from the hash).
        if (std::abs(dc - 0.5 * road) < 0.15 * step && rng.chance(0.5)) refl = 0.7f;
      }
      mesh.triangles.push_back({a, b, c});
      mesh.triangles.push_back({a, c, d});
      mesh.materials.insert(mesh.materials.end(), 2, mat);
      mesh.reflectivity.insert(mesh.reflectivity.end(), 2, refl);
    }
  }
  const auto it = m.tile_objects.find(pack(key.x, key.y));
  if (it != m.tile_objects.end()) {
    for (std::uint32_t oi : it->second) build_object_mesh(m.objects[oi], mesh);
  }
  return mesh;
}

}  // namespace litamin2::sim

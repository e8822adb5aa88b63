#include "litamin2/sim/layout.hpp"

#include <algorithm>
#include <cmath>

#include "litamin2/sim/footprint.hpp"
#include "litamin2/sim/grid.hpp"
#include "litamin2/sim/random.hpp"

namespace litamin2::sim {
namespace {

/// Places the objects of one world, layer by layer; owns the occupancy while it runs.
class Placer {
 public:
  Placer(const RoadNetwork& roads, const Ground& ground, const WorldOptions& options, Layout& out)
      : roads_(roads), ground_(ground), opt_(options), out_(out) {}

  /// Buildings, houses (with hedges or walls), garden walls and guard rails along one side.
  void frontage(int p, int side, Rng& rng) {
    double A0, L;
    if (!arc_range(p, A0, L)) return;
    const double hw = opt_.road_half_width;
    double a = A0 - 10.0;
    while (a < L + 10.0) {
      Eigen::Vector2d pos, tan;
      District d = District::kUrban;
      if (!roads_.at_arc(p, std::clamp(a, A0, L), pos, tan, d)) break;
      switch (d) {
        case District::kUrban: {
          const double w = rng.uniform(10.0, 28.0), depth = rng.uniform(10.0, 18.0);
          const double h = rng.uniform(8.0, 22.0), setback = rng.uniform(hw + 2.0, hw + 6.0);
          bool ok = opt_.buildings && rng.chance(density_chance(0.9)) &&
                    place(p, side, a + 0.5 * w, setback + 0.5 * depth, ObjectKind::kBuilding,
                          {w, depth, h}, 0.5 * w, 0.5 * depth, hw + 1.5, rng);
          if (!ok && opt_.buildings) {  // narrower retry (curves)
            ok = place(p, side, a + 0.25 * w, setback + 0.5 * depth + 2.0, ObjectKind::kBuilding,
                       {0.5 * w, depth, h}, 0.25 * w, 0.5 * depth, hw + 1.5, rng);
          }
          a += (ok ? w : 4.0) + (rng.chance(0.3) ? rng.uniform(3.0, 14.0) : rng.uniform(0.0, 0.5));
          break;
        }
        case District::kSuburban: {
          const double w = rng.uniform(8.0, 14.0), depth = rng.uniform(8.0, 12.0);
          const double h = rng.uniform(3.0, 6.5), setback = rng.uniform(hw + 5.0, hw + 14.0);
          const bool ok = opt_.buildings && rng.chance(density_chance(0.75)) &&
                          place(p, side, a + 0.5 * w, setback + 0.5 * depth, ObjectKind::kHouse,
                                {w, depth, h}, 0.5 * w + 0.5, 0.5 * depth + 0.5, hw + 1.5, rng);
          if (ok && opt_.vegetation && rng.chance(vegetation_chance(0.5))) {
            const double hl = rng.uniform(0.8, 1.5), hh = rng.uniform(0.8, 1.9);
            place(p, side, a + 0.5 * w, hw + rng.uniform(2.0, 3.5), ObjectKind::kHedge, {w, hl, hh},
                  0.5 * w, 0.5 * hl, hw + 1.0, rng);
          } else if (ok && opt_.street_furniture && rng.chance(density_chance(0.3))) {
            const double th = rng.uniform(0.2, 0.35), hh = rng.uniform(0.5, 1.8);
            place(p, side, a + 0.5 * w, hw + rng.uniform(2.0, 3.5), ObjectKind::kWall, {w, th, hh},
                  0.5 * w, 0.5 * th, hw + 1.0, rng);
          }
          a += (ok ? w : 5.0) + rng.uniform(3.0, 16.0);
          break;
        }
        case District::kGreen: {
          if (opt_.street_furniture && rng.chance(density_chance(0.15))) {
            const double w = rng.uniform(6.0, 20.0), th = rng.uniform(0.2, 0.4);
            place(p, side, a + 0.5 * w, hw + rng.uniform(3.0, 8.0), ObjectKind::kWall,
                  {w, th, rng.uniform(0.8, 2.5)}, 0.5 * w, 0.5 * th, hw + 1.0, rng);
            a += w;
          }
          a += rng.uniform(8.0, 30.0);
          break;
        }
        case District::kOpen: {
          if (opt_.street_furniture && rng.chance(density_chance(0.8))) {
            place(p, side, a + 4.0, hw + 3.5, ObjectKind::kGuardRail, {8.0, 0.2, 0.8}, 4.0, 0.2,
                  hw + 2.5, rng);
          }
          a += 8.0;
          break;
        }
      }
    }
  }

  /// Lamps, signs, street trees and runs of parked cars along the kerb of one side.
  void kerb(int p, int side, Rng& rng) {
    double A0, L;
    if (!arc_range(p, A0, L)) return;
    const double hw = opt_.road_half_width;
    double a = A0;
    double next_pole = A0 + rng.uniform(0.0, 30.0);
    while (a < L) {
      Eigen::Vector2d pos, tan;
      District d;
      if (!roads_.at_arc(p, a, pos, tan, d)) break;
      const bool open = d == District::kOpen;
      const double kerb = open ? hw + 3.5 : hw;
      // Lamps and signs.
      if (a >= next_pole) {
        if (opt_.street_furniture && rng.chance(density_chance(open ? 0.3 : 0.8))) {
          place(p, side, a, kerb + rng.uniform(0.6, 1.5), ObjectKind::kPole,
                {0.3, 0.3, rng.uniform(5.5, 9.0)}, 0.3, 0.3, kerb + 0.3, rng);
        }
        next_pole = a + (open ? rng.uniform(60.0, 200.0) : rng.uniform(22.0, 40.0));
      }
      if (opt_.street_furniture && rng.chance(density_chance(open ? 0.02 : 0.05))) {
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
      if (opt_.vegetation && rng.chance(vegetation_chance(tree_p))) {
        const double r = rng.uniform(1.5, 3.5), h = rng.uniform(2.2 * r, 4.0 * r);
        place(p, side, a + rng.uniform(0.0, 3.0), kerb + rng.uniform(1.0, 3.0) + (open ? 6.0 : 0.0),
              ObjectKind::kTree, {2 * r, 2 * r, h}, 0.6, 0.6, kerb + 0.5, rng);
      }
      // Parked cars in runs.
      const double car_p = d == District::kUrban ? 0.55 : d == District::kSuburban ? 0.3 : 0.0;
      if (opt_.parked_cars && rng.chance(density_chance(car_p))) {
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

  /// Bushes and trees scattered away from the road on one side.
  void scatter(int p, int side, Rng& rng) {
    double A0, L;
    if (!arc_range(p, A0, L)) return;
    const double hw = opt_.road_half_width;
    for (double a = A0; a < L; a += 5.0) {
      Eigen::Vector2d pos, tan;
      District d;
      if (!roads_.at_arc(p, a, pos, tan, d)) break;
      const double bush_p = d == District::kUrban      ? 0.15
                            : d == District::kSuburban ? 0.5
                            : d == District::kGreen    ? 0.9
                                                       : 0.15;
      const double tree_p = d == District::kUrban      ? 0.05
                            : d == District::kSuburban ? 0.3
                            : d == District::kGreen    ? 0.9
                                                       : 0.08;
      if (opt_.vegetation && rng.chance(vegetation_chance(bush_p))) {
        const double s = rng.uniform(0.6, 2.5);
        place(p, side, a + rng.uniform(0, 5), hw + rng.uniform(2.0, 25.0), ObjectKind::kBush,
              {s * rng.uniform(0.8, 1.6), s, s * rng.uniform(0.5, 1.0)}, 0.4 * s, 0.4 * s, hw + 0.8,
              rng);
      }
      if (opt_.vegetation && rng.chance(vegetation_chance(tree_p))) {
        const double r = rng.uniform(1.5, 4.0), h = rng.uniform(2.2 * r, 4.0 * r);
        place(p, side, a + rng.uniform(0, 5),
              hw + rng.uniform(d == District::kOpen ? 12.0 : 4.0, 30.0), ObjectKind::kTree,
              {2 * r, 2 * r, h}, 0.8, 0.8, hw + 1.0, rng);
      }
    }
  }

 private:
  /// Arc-length range [first, last] of path p; false if it has fewer than two samples.
  bool arc_range(int p, double& first, double& last) const {
    const auto& idx = roads_.path(p);
    if (idx.size() < 2) return false;
    first = roads_.sample(idx.front()).arc;
    last = roads_.sample(idx.back()).arc;
    return true;
  }

  /// True if the footprint's edge keeps `clearance` from every road and the footprint is free
  /// in the layout.
  bool footprint_free(const Footprint& f, double clearance) const {
    const bool clear = f.all_points(true, [&](const Eigen::Vector2d& q) {
      return roads_.nearest(q.x(), q.y(), clearance).second < 0;
    });
    return clear && occupied_.free(f);
  }

  /// Places an object of footprint half-sizes (hx, hy) at arc a of path p, `lateral` metres to
  /// side `side` (+1 left, -1 right), front facing the road. Returns false if rejected.
  bool place(int p, int side, double a, double lateral, ObjectKind kind,
             const Eigen::Vector3d& size, double foot_hx, double foot_hy, double clearance,
             Rng& rng) {
    Eigen::Vector2d pos, tan;
    District dist;
    if (!roads_.at_arc(p, a, pos, tan, dist)) return false;
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
    occupied_.occupy(f);
    WorldObject o;
    o.kind = kind;
    o.center = f.c;
    o.yaw = f.yaw;
    o.size = size;
    o.seed = rng.next();
    o.ground_z = ground_.height(f.c.x(), f.c.y(), dist);
    if (kind == ObjectKind::kBuilding || kind == ObjectKind::kHouse || kind == ObjectKind::kWall) {
      // Sink to the lowest ground under the footprint so no gap shows on slopes.
      const Eigen::Vector2d ex(std::cos(f.yaw), std::sin(f.yaw)), ey(-ex.y(), ex.x());
      for (int sx = -1; sx <= 1; sx += 2) {
        for (int sy = -1; sy <= 1; sy += 2) {
          const Eigen::Vector2d q = f.c + sx * f.hx * ex + sy * f.hy * ey;
          o.ground_z = std::min(o.ground_z, ground_.height(q.x(), q.y(), dist));
        }
      }
    }
    const double radius = std::hypot(size.x(), size.y()) * 0.5 + 3.0;
    out_.max_radius = std::max(out_.max_radius, radius);
    const int tx = static_cast<int>(std::floor(f.c.x() / opt_.tile_size));
    const int ty = static_cast<int>(std::floor(f.c.y() / opt_.tile_size));
    out_.tile_objects[cell_key(tx, ty)].push_back(static_cast<std::uint32_t>(out_.objects.size()));
    out_.objects.push_back(o);
    return true;
  }

  /// Probability p scaled by the density option, at most 1.
  double density_chance(double p) const { return std::min(1.0, p * opt_.density); }
  /// Probability p of a tree, bush or hedge, scaled by density and vegetation density.
  double vegetation_chance(double p) const {
    return std::min(1.0, p * opt_.density * opt_.vegetation_density);
  }

  const RoadNetwork& roads_;
  const Ground& ground_;
  const WorldOptions& opt_;
  Layout& out_;
  /// Cells covered by the objects placed so far.
  Occupancy occupied_;
};

}  // namespace

Layout lay_out(const RoadNetwork& roads, const Ground& ground, const WorldOptions& options,
               std::uint64_t seed) {
  Layout out;
  Placer placer(roads, ground, options, out);
  // Layers in a fixed order: frontage first (largest objects), then kerb items, then scatter.
  for (int layer = 0; layer < 3; ++layer) {
    for (std::size_t p = 0; p < roads.path_count(); ++p) {
      for (int side = -1; side <= 1; side += 2) {
        Rng rng(hash_combine(hash_combine(hash_combine(seed, layer), p), side + 7));
        if (layer == 0) placer.frontage(static_cast<int>(p), side, rng);
        if (layer == 1) placer.kerb(static_cast<int>(p), side, rng);
        if (layer == 2) placer.scatter(static_cast<int>(p), side, rng);
      }
    }
  }
  return out;
}

}  // namespace litamin2::sim

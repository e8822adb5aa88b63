#include "litamin2/sim/world.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <unordered_set>
#include <utility>

#include "litamin2/sim/grid.hpp"
#include "litamin2/sim/ground.hpp"
#include "litamin2/sim/layout.hpp"
#include "litamin2/sim/random.hpp"
#include "litamin2/sim/road_network.hpp"

namespace litamin2::sim {

WorldOptions WorldOptions::ground_only() {
  WorldOptions o;
  o.ground_roughness = 0.0;
  o.terrain_amplitude = 0.0;
  o.kerb_height = 0.0;
  o.density = 0.0;
  o.buildings = o.vegetation = o.street_furniture = o.parked_cars = false;
  return o;
}

/// The world's parts: its roads, the ground over them and the objects along them.
struct World::Impl {
  Impl(const std::vector<std::vector<Eigen::Isometry3d>>& sensor_paths, std::uint64_t seed,
       const WorldOptions& options)
      : opt(options),
        seed(seed),
        roads(sensor_paths, seed, options),
        ground(roads, options, seed) {}

  /// The generation options.
  WorldOptions opt;
  /// The seed the world was built from.
  std::uint64_t seed;
  /// The sampled trajectories and their districts.
  RoadNetwork roads;
  /// The ground over `roads` (refers to it).
  Ground ground;
  /// The objects placed along the roads.
  Layout layout;
  /// Keys (cell_key) of the tiles that hold geometry: ground or an object's centre.
  std::unordered_set<std::int64_t> tiles;
};

void WorldOptions::validate() const {
  if (!(tile_size > 0) || !(ground_resolution > 0)) {
    throw std::invalid_argument("World: tile_size and ground_resolution must be positive");
  }
  const std::pair<const char*, double> non_negative[] = {
      {"corridor_radius", corridor_radius},
      {"sensor_height", sensor_height},
      {"ground_roughness", ground_roughness},
      {"ground_bump_amplitude", ground_bump_amplitude},
      {"grass_height", grass_height},
      {"foliage_penetration", foliage_penetration},
      {"terrain_amplitude", terrain_amplitude},
      {"road_half_width", road_half_width},
      {"kerb_height", kerb_height},
      {"open_speed", open_speed},
      {"density", density},
      {"vegetation_density", vegetation_density}};
  for (const auto& [name, v] : non_negative) {
    if (!(v >= 0.0) || !std::isfinite(v)) {
      throw std::invalid_argument(std::string("World: ") + name + " must be finite and >= 0");
    }
  }
}

World::World(const std::vector<std::vector<Eigen::Isometry3d>>& sensor_paths, std::uint64_t seed,
             const WorldOptions& options) {
  options.validate();
  impl_ = std::make_unique<Impl>(sensor_paths, seed, options);
  if (impl_->roads.empty()) throw std::invalid_argument("World: no trajectory poses given");
  impl_->tiles = impl_->roads.corridor_tiles();
  impl_->layout = lay_out(impl_->roads, impl_->ground, options, seed);
  for (const auto& tile : impl_->layout.tile_objects) impl_->tiles.insert(tile.first);
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
  return impl_->layout.objects;
}
double World::max_object_radius() const {
  return impl_->layout.max_radius;
}

TileKey World::tile_of(const Eigen::Vector2d& xy) const {
  return {static_cast<int>(std::floor(xy.x() / impl_->opt.tile_size)),
          static_cast<int>(std::floor(xy.y() / impl_->opt.tile_size))};
}

std::vector<TileKey> World::tiles_near(const Eigen::Vector2d& xy, double radius) const {
  std::vector<TileKey> out;
  for_each_cell_near(xy, radius, impl_->opt.tile_size, [&](int x, int y) {
    if (impl_->tiles.count(cell_key(x, y))) out.push_back({x, y});
  });
  return out;
}

double World::ground_height(double x, double y) const {
  return impl_->ground.height(x, y);
}

double World::distance_to_path(double x, double y, double max_distance) const {
  return impl_->roads.nearest(x, y, max_distance).first;
}

District World::district_at(double x, double y) const {
  return impl_->roads.district_near(x, y);
}

TriangleMesh World::build_tile(const TileKey& key) const {
  const Impl& m = *impl_;
  constexpr double kLattice = RoadNetwork::kLattice;
  TriangleMesh mesh;
  if (!m.tiles.count(cell_key(key.x, key.y))) return mesh;
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
      lattice[i * ln + j] = m.roads.road_height_raw((l0x + i) * kLattice, (l0y + j) * kLattice);
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
  const District tile_district = m.roads.district_near(x0 + 0.5 * T, y0 + 0.5 * T);
  std::vector<double> dist(static_cast<std::size_t>(nv * nv));
  std::vector<District> districts(dist.size());
  mesh.vertices.resize(dist.size());
  for (int i = 0; i < nv; ++i) {
    for (int j = 0; j < nv; ++j) {
      const double x = x0 + i * step, y = y0 + j * step;
      const auto [d, si] = m.roads.nearest(x, y, 40.0);
      const District dd = si >= 0 ? m.roads.sample(si).district : tile_district;
      double z = m.ground.height(x, y, base_at(x, y), d, dd);
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
  const auto it = m.layout.tile_objects.find(cell_key(key.x, key.y));
  if (it != m.layout.tile_objects.end()) {
    for (std::uint32_t oi : it->second) build_object_mesh(m.layout.objects[oi], mesh);
  }
  return mesh;
}

}  // namespace litamin2::sim

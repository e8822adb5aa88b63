#pragma once
/// Procedural, deterministic world built around one or more sensor trajectories: ground that
/// follows the trajectories' height, building facades with relief, vegetation made of irregular
/// triangle clutter, poles, signs, parked cars, guard rails and open highway stretches. Only a
/// light layout (object descriptors) is kept for the whole trajectory; triangle meshes are made
/// on demand per square world tile, so long sequences stay memory-bounded.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "litamin2/sim/triangle_mesh.hpp"
#include "litamin2/sim/world_object.hpp"

namespace litamin2::sim {

/// Parameters of world generation.
struct WorldOptions {
  /// Edge length of a world tile (unit of mesh generation and caching), metres.
  double tile_size = 40.0;
  /// Ground exists within this distance of any trajectory, metres.
  double corridor_radius = 130.0;
  /// Height of the sensor above the road; the road surface is this far below each sensor pose.
  double sensor_height = 1.73;
  /// Ground grid spacing, metres.
  double ground_resolution = 1.0;
  /// Standard deviation of the per-vertex ground roughness, metres.
  double ground_roughness = 0.02;
  /// Amplitude of short bumps (2-5 m across: patches, sagging, ruts, lumpy verges) on and off
  /// the road, metres; 0 = none. Makes the ground non-planar within a 3 m voxel.
  double ground_bump_amplitude = 0.0;
  /// Height of the grass blades, metres: a return from grass comes from the top 10 % of the
  /// blades (a beam's footprint covers many of them); 0 = grass is a hard surface.
  double grass_height = 0.0;
  /// Mean depth a beam travels into foliage before it returns (exponential, at most 1 m),
  /// metres; 0 = returns from the first leaf triangle hit.
  double foliage_penetration = 0.0;
  /// Amplitude of low-frequency terrain (hills, embankments) away from the road, metres.
  double terrain_amplitude = 2.0;
  /// Half width of the asphalt around each trajectory, metres.
  double road_half_width = 5.5;
  /// Height of the kerb between road and sidewalk in built-up districts, metres.
  double kerb_height = 0.12;
  /// Stretches driven faster than this (m/s) become open highway with little structure.
  double open_speed = 16.0;
  /// Relative shares of urban, suburban and green stretches (open stretches come from speed).
  std::array<double, 3> district_weights = {0.55, 0.3, 0.15};
  /// Multiplies the probability of every object (0 = ground only).
  double density = 1.0;
  /// Further multiplies the probability of trees, bushes and hedges.
  double vegetation_density = 1.0;
  /// Enables building facades.
  bool buildings = true;
  /// Enables trees, bushes and hedges.
  bool vegetation = true;
  /// Enables poles, signs, guard rails and walls.
  bool street_furniture = true;
  /// Enables parked cars.
  bool parked_cars = true;

  /// A world of ground only: no objects, no roughness, no terrain, no kerb (for tests).
  static WorldOptions ground_only();
  /// Throws std::invalid_argument for a non-positive tile size or ground resolution, or a
  /// negative or non-finite height, roughness, amplitude, density or width.
  void validate() const;
};

/// Integer coordinates of a world tile: it covers [x, x+1) x [y, y+1) times tile_size.
struct TileKey {
  int x = 0;
  int y = 0;
  bool operator==(const TileKey& o) const { return x == o.x && y == o.y; }
  bool operator!=(const TileKey& o) const { return !(*this == o); }
  bool operator<(const TileKey& o) const { return x < o.x || (x == o.x && y < o.y); }
};

/// The simulated world. Immutable after construction and safe to share between threads.
class World {
 public:
  /// Builds the layout along sensor (velodyne) trajectories given in the world frame (z up).
  /// The first trajectory drives the layout; later ones (fleet vehicles) add geometry where
  /// they leave it and keep their lanes clear. Deterministic in (paths, seed, options).
  World(const std::vector<std::vector<Eigen::Isometry3d>>& sensor_paths, std::uint64_t seed,
        const WorldOptions& options = {});
  /// Single-trajectory convenience constructor.
  World(const std::vector<Eigen::Isometry3d>& sensor_path, std::uint64_t seed,
        const WorldOptions& options = {});
  ~World();
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;

  /// The seed the world was built from.
  std::uint64_t seed() const;
  /// The generation options.
  const WorldOptions& options() const;

  /// Tiles that hold geometry and come within `radius` of the point (x, y), sorted.
  std::vector<TileKey> tiles_near(const Eigen::Vector2d& xy, double radius) const;
  /// Number of tiles that hold geometry.
  std::size_t tile_count() const;
  /// The tile containing a point.
  TileKey tile_of(const Eigen::Vector2d& xy) const;
  /// Generates the triangle mesh of a tile: its ground plus every object whose centre lies in
  /// it (objects may reach a few tens of metres into neighbouring tiles). Deterministic and
  /// thread-safe.
  TriangleMesh build_tile(const TileKey& key) const;

  /// Smooth ground height (terrain and kerb, without the per-vertex roughness) at (x, y).
  double ground_height(double x, double y) const;
  /// Horizontal distance from (x, y) to the nearest trajectory, capped at `max_distance`.
  double distance_to_path(double x, double y, double max_distance = 60.0) const;
  /// District type of the trajectory stretch nearest to (x, y).
  District district_at(double x, double y) const;

  /// The placed objects (layout) of the whole world.
  const std::vector<WorldObject>& objects() const;
  /// Largest horizontal distance from an object's centre to any of its vertices, metres.
  double max_object_radius() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace litamin2::sim

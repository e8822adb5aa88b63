#pragma once
/// Embree ray casting of LiDAR scans in a simulated World. Each world tile becomes one Embree
/// geometry; the scene holds the tiles within sensor range and is rebuilt when that set changes.
/// Tiles are built on demand and kept in a bounded least-recently-used cache.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <optional>

#include "litamin2/core/point_cloud.hpp"
#include "litamin2/sim/lidar_model.hpp"
#include "litamin2/sim/material.hpp"
#include "litamin2/sim/sensor_rig.hpp"
#include "litamin2/sim/simulated_scan.hpp"
#include "litamin2/sim/traffic.hpp"
#include "litamin2/sim/world.hpp"

namespace litamin2::sim {

/// Options of the ray caster.
struct RaycasterOptions {
  /// Most tile scenes kept in memory (those in range are always kept).
  std::size_t max_cached_tiles = 192;
  /// Cast the rays of a scan in parallel with TBB (honours tbb::global_control).
  bool parallel = true;
  /// Two-level scene (one Embree scene per tile, instanced) instead of one flat scene rebuilt
  /// whenever the set of tiles in range changes. Flat is faster to trace.
  bool instancing = false;
};

/// First surface hit by a ray.
struct RayHit {
  /// Distance along the (unit) ray direction, metres.
  double range = 0.0;
  /// Unit geometric normal, oriented towards the ray origin.
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  /// Material of the hit triangle.
  Material material = Material::kAsphalt;
  /// Reflectivity of the hit triangle.
  float reflectivity = 0.0f;
};

/// One sweep to cast: where the vehicle is at its start and end, and what moves around it.
struct SweepRequest {
  /// Vehicle pose (vehicle to world, z up) at the sweep start; with an untilted mount it is
  /// the sensor pose.
  Eigen::Isometry3d start = Eigen::Isometry3d::Identity();
  /// Vehicle pose at the sweep end (start + SweepOptions::duration); used only when the rig's
  /// sweep has motion, each column then leaving from the pose interpolated between the two.
  Eigen::Isometry3d end = Eigen::Isometry3d::Identity();
  /// Time of the sweep start on the traffic's clock, seconds.
  double start_time = 0.0;
  /// Moving actors (must outlive the call), or null for none.
  const Traffic* traffic = nullptr;
};

/// Casts LiDAR scans in a World. Not thread-safe itself (scan() parallelises internally); the
/// World must outlive it.
class Raycaster {
 public:
  /// Creates the Embree device; no geometry is built until the first prepare() or scan().
  explicit Raycaster(const World& world, const RaycasterOptions& options = {});
  ~Raycaster();
  Raycaster(const Raycaster&) = delete;
  Raycaster& operator=(const Raycaster&) = delete;

  /// Makes every tile within `range` (plus the largest object radius) of `position` part of
  /// the scene, building missing tiles. scan() calls it; call it yourself before cast().
  void prepare(const Eigen::Vector3d& position, double range);

  /// Exact (noise-free) first hit of one ray in the prepared scene, if any within max_range.
  std::optional<RayHit> cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                             double max_range) const;

  /// Simulates one revolution of `model` at `sensor_pose` (sensor to world, z up) and returns
  /// the returns in the sensor frame with intensities in [0, 1]. Range noise, dropout and the
  /// reflectivity/incidence/range-dependent detection are drawn from `scan_seed`, so the same
  /// (world, pose, model, seed) gives the same bytes regardless of the thread count. Points are
  /// ordered beam by beam (top beam first), each beam by increasing azimuth.
  PointCloud scan(const Eigen::Isometry3d& sensor_pose, const LidarModel& model,
                  std::uint64_t scan_seed);

  /// Simulates one revolution of `model` installed as `rig`: columns at the rig's azimuths,
  /// each cast from its own pose when the sweep has motion; the rig's body returns self-hits;
  /// the request's traffic is cast at each column's time. Each point is in the sensor frame of its
  /// own firing (raw, as LiDAR drivers publish them: with motion the sweep is distorted, and a
  /// deskew with the firing times carries it into the frame at the sweep start, request.start
  /// times the mount rotation), with its firing time and ring;
  /// ordered by firing time (column by column, top beam first) when the sweep has motion or a
  /// non-default start/direction, else as scan(pose, ...) orders them. With a default rig and
  /// start == end the points are exactly those of scan(request.start, model, scan_seed).
  /// Throws std::invalid_argument for an invalid rig.
  SimulatedScan scan(const SweepRequest& request, const LidarModel& model, const SensorRig& rig,
                     std::uint64_t scan_seed);

  /// Tile scenes currently cached.
  std::size_t cached_tiles() const;
  /// Tile scenes in the current top-level scene.
  std::size_t active_tiles() const;
  /// Triangles in the current top-level scene.
  std::size_t active_triangles() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace litamin2::sim

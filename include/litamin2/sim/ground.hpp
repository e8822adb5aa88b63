#pragma once
/// The ground surface of a simulated World: the road surface below the trajectories plus
/// low-frequency terrain away from the road, a gentle undulation everywhere and the kerb
/// between road and sidewalk. Smooth (the per-vertex roughness of the tile meshes is not
/// part of it). Part of the World builder.

#include <cstdint>

#include "litamin2/sim/road_network.hpp"
#include "litamin2/sim/world.hpp"
#include "litamin2/sim/world_object.hpp"

namespace litamin2::sim {

/// Ground height queries over a RoadNetwork, which must outlive the Ground.
class Ground {
 public:
  /// The noise of the terrain is drawn from `seed`.
  Ground(const RoadNetwork& roads, const WorldOptions& options, std::uint64_t seed);

  /// Ground height at (x, y), with the district of the nearest road.
  double height(double x, double y) const;
  /// Ground height at (x, y) for the given district (of the road the caller is near).
  double height(double x, double y, District district) const;
  /// Ground height at (x, y) given the road height `base` below it, its distance `d` to the
  /// nearest road and the district: the one formula the tile builder and the layout share.
  double height(double x, double y, double base, double d, District district) const;

 private:
  /// Smooth value noise in [-1, 1] with unit lattice.
  double value_noise(double x, double y, std::uint64_t salt) const;

  const RoadNetwork& roads_;
  WorldOptions opt_;
  std::uint64_t seed_;
};

}  // namespace litamin2::sim

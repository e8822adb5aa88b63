#pragma once
/// The layout of a simulated World: the objects placed along its roads in three layers, each
/// side of each road with its own random stream, so the layout is deterministic in (roads,
/// seed, options). Frontage first (buildings and houses with their hedges and walls, guard
/// rails), then kerb items (lamps, signs, street trees, parked cars), then scattered bushes
/// and trees. Every object keeps a clearance from every road and does not overlap the objects
/// placed before it. Part of the World builder.

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "litamin2/sim/ground.hpp"
#include "litamin2/sim/road_network.hpp"
#include "litamin2/sim/world.hpp"
#include "litamin2/sim/world_object.hpp"

namespace litamin2::sim {

/// The placed objects and the tiles that hold them.
struct Layout {
  /// The objects, in placement order.
  std::vector<WorldObject> objects;
  /// Indices into `objects` by the key (cell_key) of the tile holding the object's centre.
  std::unordered_map<std::int64_t, std::vector<std::uint32_t>> tile_objects;
  /// Largest horizontal distance from an object's centre to any of its vertices, metres.
  double max_radius = 0.0;
};

/// Places the objects along every road of `roads`, each on the ground given by `ground`.
Layout lay_out(const RoadNetwork& roads, const Ground& ground, const WorldOptions& options,
               std::uint64_t seed);

}  // namespace litamin2::sim

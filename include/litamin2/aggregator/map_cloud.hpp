#pragma once
/// The global map as points, for viewers (rviz2's PointCloud2 display): one point per fused
/// voxel distribution of the map tiles, at its mean, with the number of points fused into it.
/// Kept per tile from the tiles the mapping thread publishes (TileOutput), so an updated tile
/// replaces its points and a tile that has gone removes them. Not thread-safe.

#include "litamin2/aggregator/aggregator_outputs.hpp"
#include "litamin2/mapping/map_tile.hpp"

#include <cstddef>
#include <cstdint>
#include <map>
#include <vector>

namespace litamin2::aggregator {

/// One map point: a fused distribution's mean (map frame, metres) and its point count.
struct MapPoint {
  float x = 0.0f;
  float y = 0.0f;
  float z = 0.0f;
  std::uint32_t count = 0;
};

class MapCloud {
 public:
  /// Replaces the tile's points by its distributions' means (an empty tile removes them).
  void update(const TileOutput& tile);
  /// Every point, by tile key, then in the tile's (voxel key) order.
  std::vector<MapPoint> points() const;
  std::size_t size() const { return size_; }
  std::size_t tiles() const { return tiles_.size(); }

 private:
  std::map<mapping::TileKey, std::vector<MapPoint>> tiles_;
  std::size_t size_ = 0;
};

}  // namespace litamin2::aggregator

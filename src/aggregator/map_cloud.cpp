#include "litamin2/aggregator/map_cloud.hpp"

#include <algorithm>

namespace litamin2::aggregator {

void MapCloud::update(const TileOutput& tile) {
  auto it = tiles_.find(tile.key);
  if (it != tiles_.end()) {
    size_ -= it->second.size();
    tiles_.erase(it);
  }
  if (tile.distributions.empty()) return;
  std::vector<MapPoint>& points = tiles_[tile.key];
  points.reserve(tile.distributions.size());
  for (const Distribution& d : tile.distributions) {
    MapPoint p;
    p.x = static_cast<float>(d.mean.x());
    p.y = static_cast<float>(d.mean.y());
    p.z = static_cast<float>(d.mean.z());
    p.count = static_cast<std::uint32_t>(std::max(d.count, 0));
    points.push_back(p);
  }
  size_ += points.size();
}

std::vector<MapPoint> MapCloud::points() const {
  std::vector<MapPoint> out;
  out.reserve(size_);
  for (const auto& [key, points] : tiles_) out.insert(out.end(), points.begin(), points.end());
  return out;
}

}  // namespace litamin2::aggregator

#include "litamin2/aggregator/aggregator_outputs.hpp"

#include <algorithm>
#include <limits>

namespace litamin2::aggregator {

StreamPoses chunk_poses(const mapping::Mapper& mapper, const PoseChunk& chunk,
                        std::uint64_t chunk_keyframes) {
  StreamPoses s;
  s.chunk = chunk.second;
  s.chunk_keyframes = chunk_keyframes;
  const mapping::StreamGroups& groups = mapper.graph().groups();
  if (chunk.first >= groups.streams().size()) return s;
  const mapping::StreamGroups::Stream& stream = groups.at(chunk.first);
  s.stream = stream.name;
  const std::string map_anchor = mapper.map_anchor();
  s.anchor = groups.at(groups.anchor_of(chunk.first)).name;
  s.in_map_frame = !map_anchor.empty() && s.anchor == map_anchor;
  if (const auto c = mapper.correction(s.stream)) s.correction = c->pose;
  const std::uint64_t first = chunk_keyframes ? chunk.second * chunk_keyframes : 0;
  const std::uint64_t end =
      chunk_keyframes ? first + chunk_keyframes : std::numeric_limits<std::uint64_t>::max();
  for (auto it = stream.nodes.lower_bound(first); it != stream.nodes.end() && it->first < end;
       ++it) {
    const mapping::KeyframeNode& n = mapper.graph().node(it->second);
    s.keyframes.push_back({n.key.id, n.stamp, n.pose});
  }
  return s;
}

std::set<PoseChunk> chunks_of(const mapping::Mapper& mapper,
                              const std::vector<std::uint32_t>& nodes,
                              std::uint64_t chunk_keyframes) {
  std::set<PoseChunk> out;
  const mapping::KeyframeGraph& graph = mapper.graph();
  for (std::uint32_t n : nodes) {
    const mapping::KeyframeNode& node = graph.node(n);
    out.emplace(node.stream, chunk_keyframes ? node.key.id / chunk_keyframes : 0);
  }
  return out;
}

std::set<PoseChunk> all_chunks(const mapping::Mapper& mapper, std::uint64_t chunk_keyframes) {
  std::set<PoseChunk> out;
  const mapping::StreamGroups& groups = mapper.graph().groups();
  for (std::uint32_t s = 0; s < groups.streams().size(); ++s) {
    const auto& nodes = groups.at(s).nodes;
    if (nodes.empty()) continue;
    if (!chunk_keyframes) {
      out.emplace(s, 0);
      continue;
    }
    // Chunk by chunk: the first id at or after each chunk's end.
    for (auto it = nodes.begin(); it != nodes.end();) {
      const std::uint64_t chunk = it->first / chunk_keyframes;
      out.emplace(s, chunk);
      it = nodes.lower_bound((chunk + 1) * chunk_keyframes);
    }
  }
  return out;
}

std::vector<StreamPoses> all_stream_poses(const mapping::Mapper& mapper) {
  std::vector<StreamPoses> out;
  for (const auto& [name, s] : mapper.graph().groups().by_name()) {
    if (mapper.graph().groups().at(s).nodes.empty()) continue;
    out.push_back(chunk_poses(mapper, {s, 0}, 0));
  }
  return out;
}

MapSummary map_summary(const mapping::Mapper& mapper, const mapping::TileMap& tiles,
                       std::size_t max_means) {
  MapSummary s;
  s.anchor = mapper.map_anchor();
  s.voxel_size = mapper.config().map_voxel_size;
  s.tile_size = tiles.geometry().tile_size;
  const mapping::MapperStats stats = mapper.stats();
  s.keyframes = stats.keyframes;
  s.streams = stats.streams;
  s.loops = mapper.loops().size();
  s.optimizations = stats.optimizations;
  s.pending_keyframes = tiles.pending();
  const mapping::TileMapStats t = tiles.stats();
  s.voxels = t.distributions;
  s.tiles = t.tiles;
  std::size_t samples = 0;
  bool first = true;
  for (const auto& [key, tile] : tiles.index()) {
    samples += tile.sample.size();
    if (tile.distributions == 0) continue;
    if (first) {
      s.min_bound = tile.min_bound.cast<double>();
      s.max_bound = tile.max_bound.cast<double>();
      first = false;
    }
    s.min_bound = s.min_bound.cwiseMin(tile.min_bound.cast<double>());
    s.max_bound = s.max_bound.cwiseMax(tile.max_bound.cast<double>());
  }
  const std::size_t n = std::min(max_means, samples);
  if (n == 0) return s;
  s.means.reserve(n);
  // The i-th of n evenly spaced samples of all, walking the tiles in key order.
  std::size_t seen = 0, next = 0;
  for (const auto& [key, tile] : tiles.index()) {
    for (const Eigen::Vector3f& m : tile.sample) {
      if (s.means.size() < n && seen == next * samples / n) {
        s.means.push_back(m);
        ++next;
      }
      ++seen;
    }
  }
  return s;
}

TileOutput tile_output(const mapping::Mapper& mapper, mapping::TileMap& tiles,
                       mapping::TileKey key) {
  TileOutput out;
  out.key = key;
  out.tile_size = tiles.geometry().tile_size;
  out.voxel_size = tiles.geometry().voxels.voxel_size;
  out.anchor = mapper.map_anchor();
  if (const auto tile = tiles.tile(key)) {
    out.keyframes = tile->keyframes();
    out.distributions = tile->distributions(tiles.geometry());
  }
  return out;
}

}  // namespace litamin2::aggregator

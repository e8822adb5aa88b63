#pragma once
/// What the aggregator publishes, in the mapper's types, and how it is read off the mapper:
/// corrected keyframe poses per stream in chunks of consecutive keyframe ids, the map tiles
/// and the map's summary. The DDS node turns them into litamin2/msg/KeyframePoses, MapTile and
/// MapSummary; export writes the same poses to files.
///
/// Each costs what it carries: a chunk reads its own keyframes, a tile its own voxels, and the
/// summary the tile index (one entry per tile), never every keyframe of the map.

#include "litamin2/mapping/mapper.hpp"
#include "litamin2/mapping/tile_map.hpp"

#include <Eigen/Geometry>
#include <cstdint>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace litamin2::aggregator {

struct StreamPoses {
  std::string stream;
  /// The stream whose odometry frame the poses are in (the first stream of its loop group).
  std::string anchor;
  /// anchor is the map's anchor stream: the poses are in the shared map frame.
  bool in_map_frame = false;
  /// corrected = correction * odometry pose, for the stream's latest keyframe.
  Eigen::Isometry3d correction = Eigen::Isometry3d::Identity();
  /// The keyframes with ids in [chunk * chunk_keyframes, (chunk + 1) * chunk_keyframes)
  /// (chunk_keyframes 0: every keyframe of the stream, chunk 0).
  std::uint64_t chunk = 0;
  std::uint64_t chunk_keyframes = 0;
  struct Entry {
    std::uint64_t id = 0;
    Stamp stamp;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  };
  /// The chunk's keyframes present, by id.
  std::vector<Entry> keyframes;
};

/// A chunk of a stream's keyframes: (stream index in StreamGroups, chunk number).
using PoseChunk = std::pair<std::uint32_t, std::uint64_t>;

struct MapSummary {
  /// The stream whose odometry frame is the map frame ("" when there is no keyframe).
  std::string anchor;
  double voxel_size = 0.0;
  double tile_size = 0.0;
  /// Distributions in the tiles, and tiles.
  std::size_t voxels = 0;
  std::size_t tiles = 0;
  std::size_t keyframes = 0;
  std::size_t streams = 0;
  std::size_t loops = 0;
  std::size_t optimizations = 0;
  /// Keyframes that arrived or moved and are not fused into the tiles yet.
  std::size_t pending_keyframes = 0;
  /// Bounding box of the voxel means (zero when there are none).
  Eigen::Vector3d min_bound = Eigen::Vector3d::Zero();
  Eigen::Vector3d max_bound = Eigen::Vector3d::Zero();
  /// At most max_means voxel means, decimated evenly from the tiles' samples (by tile key).
  std::vector<Eigen::Vector3f> means;
};

/// One map tile's fused distributions, in the map frame.
struct TileOutput {
  mapping::TileKey key;
  double tile_size = 0.0;
  double voxel_size = 0.0;
  /// The map frame's anchor stream.
  std::string anchor;
  std::int64_t keyframes = 0;
  /// Ordered by voxel key; empty when the tile has gone (no keyframe in it any more).
  std::vector<Distribution> distributions;
};

/// One chunk's corrected poses (an unknown stream gives an empty StreamPoses).
StreamPoses chunk_poses(const mapping::Mapper& mapper, const PoseChunk& chunk,
                        std::uint64_t chunk_keyframes);
/// The chunks holding the given nodes (KeyframeGraph numbering).
std::set<PoseChunk> chunks_of(const mapping::Mapper& mapper,
                              const std::vector<std::uint32_t>& nodes,
                              std::uint64_t chunk_keyframes);
/// Every chunk of every stream.
std::set<PoseChunk> all_chunks(const mapping::Mapper& mapper, std::uint64_t chunk_keyframes);
/// Every stream's poses in one piece each (chunk_keyframes 0), ordered by stream id.
std::vector<StreamPoses> all_stream_poses(const mapping::Mapper& mapper);

/// The summary, from the tile index.
MapSummary map_summary(const mapping::Mapper& mapper, const mapping::TileMap& tiles,
                       std::size_t max_means);
/// A tile's contents (empty distributions when the map has no such tile).
TileOutput tile_output(const mapping::Mapper& mapper, mapping::TileMap& tiles,
                       mapping::TileKey key);

}  // namespace litamin2::aggregator

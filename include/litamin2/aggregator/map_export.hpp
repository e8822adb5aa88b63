#pragma once
/// `litamin2-aggregator export`: the map and trajectories of a store, rebuilt offline.
///
/// The store is opened read-only (never modified) and its graph recovered as the aggregator
/// does at start (from the indexed tables: the state the aggregator last committed, with its
/// map tiles, in which the keyframes not fused yet are then fused in memory), or, with
/// `replay`, rebuilt by loading every keyframe in canonical order into a new mapper (a state
/// that depends only on the set of stored keyframes, O(N) registrations; its tiles made from
/// all of them); then written:
///  - the global map as a binary PLY (`.ply`) or binary PCD v0.7 (`.pcd`), chosen by the file
///    name's extension, one vertex/point per distribution with float properties/fields
///    x y z (mean), c00 c01 c02 c11 c12 c22 (covariance), nx ny nz (unit normal: the
///    covariance's least eigenvector, nz >= 0) and count (PCD: U 4): the tiles' distributions, tile
///    by tile (by tile key, then voxel key), only those whose mean lies in the bounding box if one
///    is given (only the tiles that meet it are read);
///  - per stream `<stream>_kitti.txt` (KITTI, 12 numbers per line) and `<stream>_tum.txt`
///    (TUM, stamp in seconds) of the corrected keyframe poses, by keyframe id, in the frame of
///    the stream's anchor (the map frame for streams joined to the map); '/' in a stream id
///    becomes "__" in file names (stream ids never contain "__").

#include "litamin2/aggregator/aggregator_core.hpp"
#include "litamin2/aggregator/aggregator_outputs.hpp"
#include "litamin2/mapping/mapper_config.hpp"

#include <optional>
#include <string>
#include <vector>

namespace litamin2::aggregator {

/// The map file's format, by its name's extension (case-insensitive).
enum class MapFormat { kPly, kPcd };

/// .ply or .pcd; std::nullopt for any other extension (which export_store refuses).
std::optional<MapFormat> map_format(const std::string& path);

struct ExportOptions {
  std::string store;
  /// Empty: no map file; otherwise a .ply or .pcd (map_format).
  std::string map_file;
  /// Empty: no trajectories.
  std::string trajectories_dir;
  mapping::MapperConfig mapper;
  AggregatorCore::Progress progress;
  /// Rebuild the graph from the keyframes instead of reading it from the tables.
  bool replay = false;
  /// The map tiles' geometry (the aggregator's map_tiles section).
  mapping::TileMapConfig tiles;
  /// Only the map within x in [min_x, max_x] and y in [min_y, max_y] (map frame, metres).
  struct Box {
    double min_x = 0.0, min_y = 0.0, max_x = 0.0, max_y = 0.0;
  };
  std::optional<Box> box;
};

struct ExportResult {
  std::size_t keyframes = 0;
  std::size_t streams = 0;
  std::size_t loops = 0;
  std::size_t voxels = 0;
  /// Tiles the map was read from.
  std::size_t tiles = 0;
  std::vector<std::string> files;
};

/// Throws store::StoreError (naming the file) if the store cannot be read, io::IoError if an
/// output cannot be written, std::invalid_argument (before opening the store) if map_file has
/// neither a .ply nor a .pcd extension.
ExportResult export_store(const ExportOptions& options);

/// The PLY described above.
void write_map_ply(const std::string& path, const std::vector<Distribution>& map);
/// The same columns as a binary PCD (x y z as the points, the rest as extra fields).
void write_map_pcd(const std::string& path, const std::vector<Distribution>& map);
/// The map's distributions in the box (every one without), tile by tile; `tiles_read` counts
/// the tiles read.
std::vector<Distribution> map_in_box(mapping::TileMap& tiles,
                                     const std::optional<ExportOptions::Box>& box,
                                     std::size_t* tiles_read = nullptr);
/// File name stem of a stream ("fleet/car1" -> "fleet__car1").
std::string stream_file_stem(const std::string& stream);
/// Writes DIR/<stem>_kitti.txt and DIR/<stem>_tum.txt (creating DIR); returns the paths.
std::vector<std::string> write_trajectories(const std::string& dir, const StreamPoses& poses);

}  // namespace litamin2::aggregator

#include "litamin2/dds/map_tile_conversion.hpp"

#include "litamin2/core/value_checks.hpp"
#include "litamin2/dds/distribution_conversion.hpp"
#include "litamin2/dds/map_patch_conversion.hpp"
#include "litamin2/dds/time_conversion.hpp"
#include "litamin2/service/topic_names.hpp"

#include <cmath>

namespace litamin2::dds {
namespace {

constexpr std::uint32_t kNsPerSecond = 1'000'000'000;

TileConversion rejected(TileError error, std::string message) {
  TileConversion out;
  out.error = error;
  out.message = std::move(message);
  return out;
}

/// v is in tile `i`'s interval along one axis, [i size, (i + 1) size], widened by margin.
bool within(double v, std::int32_t i, double tile_size, double margin) {
  const double lo = static_cast<double>(i) * tile_size;
  return v >= lo - margin && v <= lo + tile_size + margin;
}

}  // namespace

litamin2::msg::MapTile to_map_tile(const MapTileData& tile) {
  litamin2::msg::MapTile msg;
  msg.ix(tile.ix);
  msg.iy(tile.iy);
  msg.tile_size(static_cast<float>(tile.tile_size));
  msg.voxel_size(static_cast<float>(tile.voxel_size));
  msg.revision(tile.revision);
  msg.stamp(to_time(tile.stamp));
  msg.frame_id(tile.frame_id);
  msg.anchor_stream(tile.anchor_stream);
  msg.keyframes(tile.keyframes);
  auto& out = msg.distributions();
  out.resize(tile.distributions.size());
  for (std::size_t i = 0; i < tile.distributions.size(); ++i)
    out[i] = to_voxel_distribution(tile.distributions[i]);
  return msg;
}

const char* to_string(TileError error) {
  switch (error) {
    case TileError::kNone:
      return "none";
    case TileError::kBadTileSize:
      return "bad_tile_size";
    case TileError::kBadVoxelSize:
      return "bad_voxel_size";
    case TileError::kBadKey:
      return "bad_key";
    case TileError::kBadStamp:
      return "bad_stamp";
    case TileError::kBadFrame:
      return "bad_frame";
    case TileError::kBadKeyframes:
      return "bad_keyframes";
    case TileError::kTooManyDistributions:
      return "too_many_distributions";
    case TileError::kBadDistribution:
      return "bad_distribution";
    case TileError::kOutsideTile:
      return "outside_tile";
  }
  return "unknown";
}

std::vector<TileError> all_tile_errors() {
  return {TileError::kBadTileSize,
          TileError::kBadVoxelSize,
          TileError::kBadKey,
          TileError::kBadStamp,
          TileError::kBadFrame,
          TileError::kBadKeyframes,
          TileError::kTooManyDistributions,
          TileError::kBadDistribution,
          TileError::kOutsideTile};
}

TileConversion from_map_tile(const litamin2::msg::MapTile& msg,
                             const TileConversionOptions& options) {
  const std::string where =
      "tile (" + std::to_string(msg.ix()) + ", " + std::to_string(msg.iy()) + "): ";
  const float tile_size = msg.tile_size();
  if (!(tile_size >= kMinTileSize && tile_size <= kMaxTileSize))
    return rejected(TileError::kBadTileSize, where + "tile size " + checks::number_text(tile_size) +
                                                 " is not in [1, 100000] m");
  const float voxel_size = msg.voxel_size();
  if (!(voxel_size >= kMinVoxelSize && voxel_size <= kMaxVoxelSize))
    return rejected(
        TileError::kBadVoxelSize,
        where + "voxel size " + checks::number_text(voxel_size) + " is not in [0.05, 50] m");
  const double size = tile_size;
  const double x0 = msg.ix() * size, y0 = msg.iy() * size;
  if (std::fabs(x0) > checks::kMaxPosition || std::fabs(x0 + size) > checks::kMaxPosition ||
      std::fabs(y0) > checks::kMaxPosition || std::fabs(y0 + size) > checks::kMaxPosition)
    return rejected(TileError::kBadKey, where + "the tile's square is beyond +-" +
                                            checks::number_text(checks::kMaxPosition) + " m");
  if (msg.stamp().nanosec() >= kNsPerSecond)
    return rejected(TileError::kBadStamp,
                    where + "stamp nanosec " + std::to_string(msg.stamp().nanosec()) + " >= 1e9");
  if (msg.frame_id().empty() || msg.frame_id().size() > kMaxFrameIdLength)
    return rejected(
        TileError::kBadFrame,
        where + "frame id of " + std::to_string(msg.frame_id().size()) + " characters (1 to 256)");
  if (!msg.anchor_stream().empty()) {
    if (const auto why = service::stream_id_error(msg.anchor_stream()))
      return rejected(TileError::kBadFrame, where + "anchor stream: " + *why);
  }
  const auto& in = msg.distributions();
  if (!in.empty() && msg.keyframes() == 0)
    return rejected(TileError::kBadKeyframes,
                    where + std::to_string(in.size()) + " distributions but no keyframe");
  if (options.max_distributions > 0 && in.size() > options.max_distributions)
    return rejected(TileError::kTooManyDistributions,
                    where + std::to_string(in.size()) + " distributions > limit " +
                        std::to_string(options.max_distributions));

  TileConversion out;
  MapTileData& tile = out.tile;
  tile.ix = msg.ix();
  tile.iy = msg.iy();
  tile.tile_size = tile_size;
  tile.voxel_size = voxel_size;
  tile.revision = msg.revision();
  tile.stamp = to_stamp(msg.stamp());
  tile.frame_id = msg.frame_id();
  tile.anchor_stream = msg.anchor_stream();
  tile.keyframes = msg.keyframes();
  tile.distributions.resize(in.size());
  const double margin = voxel_size;
  for (std::size_t i = 0; i < in.size(); ++i) {
    Distribution& d = tile.distributions[i];
    if (const auto why = convert_distribution(in[i], d))
      return rejected(TileError::kBadDistribution,
                      where + "distribution " + std::to_string(i) + ": " + *why);
    if (!within(d.mean.x(), tile.ix, size, margin) || !within(d.mean.y(), tile.iy, size, margin))
      return rejected(TileError::kOutsideTile, where + "distribution " + std::to_string(i) +
                                                   ": mean (" + checks::number_text(d.mean.x()) +
                                                   ", " + checks::number_text(d.mean.y()) +
                                                   ") is outside the tile");
  }
  return out;
}

}  // namespace litamin2::dds

// Fuzz harness: a litamin2/msg/MapTile as a map tile client (litamin2-map-tiles) receives it,
// from raw CDR bytes through a dds::CheckedType to dds::from_map_tile, and the tile box filter's
// key reading of the same bytes. Properties: nothing throws; a rejected tile gives no
// distributions and a reason; an accepted one has a valid size, voxel size and frame, bounded
// means inside its square widened by a voxel edge, PSD covariances and counts >= 1, and the
// aggregator's conversion sends it again unchanged; the filter reads the key the conversion
// accepted (plain CDR).

#include "cdr_payload.hpp"
#include "fuzz_support.hpp"
#include "litamin2/dds/map_patch_conversion.hpp"
#include "litamin2/dds/map_tile_conversion.hpp"
#include "litamin2/dds/tile_box_filter.hpp"
#include "litamin2/msg/MapTilePubSubTypes.h"

#include <cmath>

using namespace litamin2;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static dds::CheckedType<litamin2::msg::MapTilePubSubType> type(1 << 20);
  const auto key = dds::serialized_tile_key(data, size);  // any bytes: never reads past them
  litamin2::msg::MapTile msg;
  if (!fuzz::deserialize(type, data, size, msg)) return 0;
  dds::TileConversionOptions options;
  options.max_distributions = 4096;
  const dds::TileConversion c = dds::from_map_tile(msg, options);
  if (!c.ok()) {
    LITAMIN2_FUZZ_CHECK(c.tile.distributions.empty() && !c.message.empty(),
                        "rejected: no distributions, reason");
    return 0;
  }
  fuzz::accepted() = true;
  const dds::MapTileData& t = c.tile;
  // The filter reads plain CDR (what Fast DDS writes); other encapsulations it keeps out.
  const bool plain_cdr = size >= 2 && data[0] == 0 && data[1] <= 1;
  LITAMIN2_FUZZ_CHECK(!plain_cdr || (key && key->first == t.ix && key->second == t.iy),
                      "filter key");
  LITAMIN2_FUZZ_CHECK(t.tile_size >= dds::kMinTileSize && t.tile_size <= dds::kMaxTileSize,
                      "tile size");
  LITAMIN2_FUZZ_CHECK(t.voxel_size >= dds::kMinVoxelSize && t.voxel_size <= dds::kMaxVoxelSize,
                      "voxel size");
  LITAMIN2_FUZZ_CHECK(!t.frame_id.empty(), "frame id");
  LITAMIN2_FUZZ_CHECK(t.distributions.empty() || t.keyframes > 0, "keyframes");
  const double x0 = t.ix * t.tile_size - t.voxel_size, y0 = t.iy * t.tile_size - t.voxel_size;
  const double span = t.tile_size + 2 * t.voxel_size;
  for (const Distribution& d : t.distributions) {
    LITAMIN2_FUZZ_CHECK(!checks::position_error(d.mean), "distribution mean");
    LITAMIN2_FUZZ_CHECK(
        d.mean.x() >= x0 && d.mean.x() <= x0 + span && d.mean.y() >= y0 && d.mean.y() <= y0 + span,
        "mean inside the tile");
    const auto cov = checks::covariance_error<3>(d.cov);
    LITAMIN2_FUZZ_CHECK(!cov, "distribution covariance " + cov.value_or(""));
    LITAMIN2_FUZZ_CHECK(d.shape_cov_inv.allFinite(), "distribution inverse finite");
    LITAMIN2_FUZZ_CHECK(d.count >= 1, "distribution count >= 1");
  }
  const dds::TileConversion again = dds::from_map_tile(dds::to_map_tile(t), options);
  LITAMIN2_FUZZ_CHECK(again.ok(),
                      "the aggregator's conversion of an accepted tile: " + again.message);
  LITAMIN2_FUZZ_CHECK(again.tile.distributions.size() == t.distributions.size() &&
                          again.tile.revision == t.revision,
                      "round trip");
  return 0;
}

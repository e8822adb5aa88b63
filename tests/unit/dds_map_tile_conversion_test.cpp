// MapTile <-> MapTileData: the round trip, each rejection, and the tile box filter's reading of
// the key off the serialised sample.

#include "litamin2/dds/map_tile_conversion.hpp"
#include "litamin2/dds/tile_box_filter.hpp"
#include "litamin2/msg/MapTilePubSubTypes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace litamin2;

namespace {

/// Tile (2, -3) of 10 m with 1 m voxels: means inside [20, 30) x [-30, -20).
dds::MapTileData sample_tile() {
  dds::MapTileData t;
  t.ix = 2;
  t.iy = -3;
  t.tile_size = 10.0;
  t.voxel_size = 1.0;
  t.revision = 1'700'000'000'000'123;
  t.stamp.nanoseconds = 1'700'000'000'123'456'789;
  t.frame_id = "map";
  t.anchor_stream = "fleet/car_1";
  t.keyframes = 7;
  for (int i = 0; i < 20; ++i) {
    Distribution d;
    // Float-representable values: the trip through floats is exact.
    d.mean = Eigen::Vector3d(20.25 + 0.5 * i, -29.5 + 0.25 * i, 0.125 * (i % 5));
    d.cov << 0.5, 0.0625, 0.03125, 0.0625, 0.25, 0.015625, 0.03125, 0.015625, 0.125;
    d.count = 4 + i;
    t.distributions.push_back(d);
  }
  return t;
}

dds::TileError error_of(const litamin2::msg::MapTile& msg, dds::TileConversionOptions o = {}) {
  const dds::TileConversion c = dds::from_map_tile(msg, o);
  if (!c.ok()) {
    EXPECT_FALSE(c.message.empty());
    EXPECT_TRUE(c.tile.distributions.empty());
  }
  return c.error;
}

}  // namespace

TEST(MapTileConversion, RoundTrip) {
  const dds::MapTileData t = sample_tile();
  const dds::TileConversion c = dds::from_map_tile(dds::to_map_tile(t));
  ASSERT_TRUE(c.ok()) << c.message;
  EXPECT_EQ(c.tile.ix, t.ix);
  EXPECT_EQ(c.tile.iy, t.iy);
  EXPECT_EQ(c.tile.tile_size, t.tile_size);
  EXPECT_EQ(c.tile.voxel_size, t.voxel_size);
  EXPECT_EQ(c.tile.revision, t.revision);
  EXPECT_EQ(c.tile.stamp.nanoseconds, t.stamp.nanoseconds);
  EXPECT_EQ(c.tile.frame_id, t.frame_id);
  EXPECT_EQ(c.tile.anchor_stream, t.anchor_stream);
  EXPECT_EQ(c.tile.keyframes, t.keyframes);
  ASSERT_EQ(c.tile.distributions.size(), t.distributions.size());
  for (std::size_t i = 0; i < t.distributions.size(); ++i) {
    EXPECT_EQ(c.tile.distributions[i].mean, t.distributions[i].mean);
    EXPECT_EQ(c.tile.distributions[i].cov, t.distributions[i].cov);
    EXPECT_EQ(c.tile.distributions[i].count, t.distributions[i].count);
  }
}

TEST(MapTileConversion, AGoneTileIsValid) {
  dds::MapTileData t = sample_tile();
  t.distributions.clear();
  t.keyframes = 0;
  EXPECT_TRUE(dds::from_map_tile(dds::to_map_tile(t)).ok());
}

TEST(MapTileConversion, MeansWithinHalfAVoxelOfTheSquareAreInside) {
  dds::MapTileData t = sample_tile();
  t.distributions[0].mean.x() = 19.5;    // its voxel [19, 20) has its centre 19.5 in tile 1...
  t.distributions[1].mean.y() = -19.75;  // ... a fused mean stays in the voxel of its centre
  EXPECT_TRUE(dds::from_map_tile(dds::to_map_tile(t)).ok());
}

TEST(MapTileConversion, RejectsEachBadField) {
  const litamin2::msg::MapTile good = dds::to_map_tile(sample_tile());
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  auto with = [&](auto change) {
    litamin2::msg::MapTile m = good;
    change(m);
    return m;
  };
  using E = dds::TileError;
  EXPECT_EQ(error_of(with([&](auto& m) { m.tile_size(nan); })), E::kBadTileSize);
  EXPECT_EQ(error_of(with([&](auto& m) { m.tile_size(0.5f); })), E::kBadTileSize);
  EXPECT_EQ(error_of(with([&](auto& m) { m.tile_size(inf); })), E::kBadTileSize);
  EXPECT_EQ(error_of(with([&](auto& m) { m.voxel_size(0.0f); })), E::kBadVoxelSize);
  EXPECT_EQ(error_of(with([&](auto& m) { m.voxel_size(nan); })), E::kBadVoxelSize);
  EXPECT_EQ(error_of(with([&](auto& m) {
              m.ix(std::numeric_limits<std::int32_t>::max());
              m.tile_size(100.0f);
            })),
            E::kBadKey);
  EXPECT_EQ(error_of(with([&](auto& m) { m.stamp().nanosec(1'000'000'000); })), E::kBadStamp);
  EXPECT_EQ(error_of(with([&](auto& m) { m.frame_id(""); })), E::kBadFrame);
  EXPECT_EQ(error_of(with([&](auto& m) { m.frame_id(std::string(300, 'm')); })), E::kBadFrame);
  EXPECT_EQ(error_of(with([&](auto& m) { m.anchor_stream("bad stream"); })), E::kBadFrame);
  EXPECT_EQ(error_of(with([&](auto& m) { m.keyframes(0); })), E::kBadKeyframes);
  dds::TileConversionOptions small;
  small.max_distributions = 5;
  EXPECT_EQ(error_of(good, small), E::kTooManyDistributions);
  EXPECT_EQ(error_of(with([&](auto& m) { m.distributions()[3].mean()[2] = nan; })),
            E::kBadDistribution);
  EXPECT_EQ(error_of(with([&](auto& m) { m.distributions()[3].cov()[0] = -1.0f; })),
            E::kBadDistribution);
  EXPECT_EQ(error_of(with([&](auto& m) { m.distributions()[3].count(0); })), E::kBadDistribution);
  // Outside the square by more than a voxel edge, in x or in y.
  EXPECT_EQ(error_of(with([&](auto& m) { m.distributions()[2].mean()[0] = 18.5f; })),
            E::kOutsideTile);
  EXPECT_EQ(error_of(with([&](auto& m) { m.distributions()[2].mean()[1] = -18.5f; })),
            E::kOutsideTile);
  EXPECT_EQ(error_of(with([&](auto& m) { m.ix(5); })), E::kOutsideTile);
}

TEST(MapTileConversion, ErrorNamesAreDistinct) {
  std::set<std::string> names;
  for (const dds::TileError e : dds::all_tile_errors()) names.insert(dds::to_string(e));
  EXPECT_EQ(names.size(), dds::all_tile_errors().size());
  EXPECT_EQ(names.count("none"), 0u);
}

TEST(TileBoxFilter, ParametersRoundTripAndBadOnesAreRefused) {
  const dds::TileBox box{-4, 7, -2147483647 - 1, 2147483647};
  const auto back = dds::parse_tile_box(dds::tile_box_parameters(box));
  ASSERT_TRUE(back);
  EXPECT_EQ(back->ix_min, box.ix_min);
  EXPECT_EQ(back->ix_max, box.ix_max);
  EXPECT_EQ(back->iy_min, box.iy_min);
  EXPECT_EQ(back->iy_max, box.iy_max);
  EXPECT_FALSE(dds::parse_tile_box({"1", "2", "3"}));
  EXPECT_FALSE(dds::parse_tile_box({"1", "2", "3", "x"}));
  EXPECT_FALSE(dds::parse_tile_box({"1", "2", "3", "4 "}));
  EXPECT_FALSE(dds::parse_tile_box({"1", "2", "3", "2147483648"}));
  EXPECT_FALSE(dds::parse_tile_box({"3", "2", "0", "0"}));  // min > max
}

TEST(TileBoxFilter, ReadsTheKeyOffTheSerialisedSample) {
  litamin2::msg::MapTilePubSubType type;
  for (const auto& [ix, iy] : std::vector<std::pair<int, int>>{{2, -3}, {-70000, 123456}}) {
    dds::MapTileData t = sample_tile();
    t.ix = ix;
    t.iy = iy;
    litamin2::msg::MapTile msg = dds::to_map_tile(t);
    eprosima::fastrtps::rtps::SerializedPayload_t payload(type.getSerializedSizeProvider(&msg)());
    ASSERT_TRUE(type.serialize(&msg, &payload));
    const auto key = dds::serialized_tile_key(payload.data, payload.length);
    ASSERT_TRUE(key);
    EXPECT_EQ(key->first, ix);
    EXPECT_EQ(key->second, iy);
    EXPECT_FALSE(dds::serialized_tile_key(payload.data, 11));
    payload.data[1] = 0x02;  // not plain CDR
    EXPECT_FALSE(dds::serialized_tile_key(payload.data, payload.length));
  }
}

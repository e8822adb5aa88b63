// The map's points kept per tile (aggregator/map_cloud.hpp): a tile's points are its
// distributions' means with their counts, an updated tile replaces them, an empty one removes
// them.

#include "litamin2/aggregator/map_cloud.hpp"

#include <gtest/gtest.h>

using namespace litamin2;
using namespace litamin2::aggregator;

namespace {

TileOutput tile(std::int32_t ix, std::vector<Eigen::Vector3d> means) {
  TileOutput t;
  t.key = mapping::TileKey{ix, 0};
  int count = 10;
  for (const Eigen::Vector3d& m : means) {
    Distribution d;
    d.mean = m;
    d.count = count++;
    t.distributions.push_back(d);
  }
  t.keyframes = t.distributions.empty() ? 0 : 1;
  return t;
}

}  // namespace

TEST(MapCloud, TilesAddReplaceAndRemoveTheirPoints) {
  MapCloud cloud;
  cloud.update(tile(1, {{100.5, 2.25, -1.0}, {101.0, 3.0, 0.5}}));
  cloud.update(tile(0, {{1.0, 2.0, 3.0}}));
  ASSERT_EQ(cloud.size(), 3u);
  EXPECT_EQ(cloud.tiles(), 2u);
  std::vector<MapPoint> p = cloud.points();
  // By tile key: tile 0 first.
  EXPECT_EQ(p[0].x, 1.0f);
  EXPECT_EQ(p[0].count, 10u);
  EXPECT_EQ(p[1].x, 100.5f);
  EXPECT_EQ(p[1].y, 2.25f);
  EXPECT_EQ(p[1].z, -1.0f);
  EXPECT_EQ(p[2].count, 11u);

  cloud.update(tile(1, {{5.0, 6.0, 7.0}}));  // the tile changed: its old points go
  p = cloud.points();
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[1].x, 5.0f);
  EXPECT_EQ(cloud.size(), 2u);

  cloud.update(tile(0, {}));  // the tile has gone
  ASSERT_EQ(cloud.size(), 1u);
  EXPECT_EQ(cloud.tiles(), 1u);
  EXPECT_EQ(cloud.points()[0].z, 7.0f);
}

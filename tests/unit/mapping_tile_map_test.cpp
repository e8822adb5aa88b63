// The tiled global map kept up to date by the change: after keyframes arrive out of order,
// groups join the map, the map frame moves to another group, loops move keyframes and updates
// are deferred (a small budget per call) and tiles evicted and read back, every tile equals a
// full rebuild (every keyframe fused once, at the pose the incremental map holds it at) to
// rounding; with a zero move threshold the tiles hold the global map's distributions. In
// segment mode (TileMapConfig::segment_keyframes > 0, the default) the full rebuild fuses every
// segment once (reference = its lowest id, frame = the reference's fused pose, each keyframe at
// its fused pose relative to it) and places it; its fused mass (count, first and second
// moments about the map origin) equals that of the keyframes fused one by one.

#include "litamin2/core/config_error.hpp"
#include "litamin2/core/voxel_key.hpp"
#include "litamin2/mapping/mapper.hpp"
#include "litamin2/mapping/segment_voxels.hpp"
#include "litamin2/mapping/tile_map.hpp"
#include "support/street_drive.hpp"

#include <gtest/gtest.h>

#include <map>

using namespace litamin2;
using namespace litamin2::mapping;
using litamin2::testing::drive;
using litamin2::testing::out_and_back;

namespace {

MapperConfig street_config() {
  MapperConfig config;
  config.place.min_travel_gap = 20.0;
  // b joins a's group at their first loop (the tiles' test of a group joining the map; the
  // merge confirmation is mapping_merge_confirmation_test's and TwoVehicles').
  config.place.merge_confirmations = 1;
  return config;
}

/// a drives the street out and back with drift; b drives its second half later and starts
/// from far away in its own frame, but its keyframes arrive first (so b is the map until a's
/// first keyframe arrives, then a group that a loop joins to a's).
std::vector<Keyframe> arrivals() {
  const auto truth = out_and_back();
  std::vector<Keyframe> a = drive("a", truth, 0.05, 1);
  std::vector<Keyframe> b = drive("b", {truth.begin() + 21, truth.end()}, 0.0, 2);
  for (auto& kf : b) kf.stamp.nanoseconds += 10'000'000'000;
  std::vector<Keyframe> out(b.begin(), b.begin() + 8);
  for (std::size_t i = 0; i < a.size(); ++i) {
    out.push_back(a[i]);
    if (8 + i < b.size()) out.push_back(b[8 + i]);
  }
  std::swap(out[10], out[12]);  // and one late keyframe
  return out;
}

/// Every keyframe fused once at the pose `map` holds it at.
std::map<TileKey, MapTile> full_rebuild(const Mapper& mapper, const TileMap& map) {
  std::map<TileKey, MapTile> tiles;
  const KeyframeGraph& graph = mapper.graph();
  for (const auto& [key, n] : graph.by_key()) {
    const auto pose = map.fused_pose(n);
    if (!pose) continue;
    std::map<TileKey, bool> seen;
    for (const FusedMoment& m : fused_moments(*mapper.cache().get(key), *pose, map.geometry())) {
      MapTile& t = tiles.try_emplace(m.tile, m.tile).first->second;
      if (!seen[m.tile]) t.count_keyframe(+1);
      seen[m.tile] = true;
      EXPECT_TRUE(t.apply(m.voxel, m.moments, +1));
    }
  }
  return tiles;
}

/// Segment mode: every segment fused once from the poses `map` holds its keyframes at.
std::map<TileKey, MapTile> segment_rebuild(const Mapper& mapper, const TileMap& map,
                                           int segment_keyframes) {
  const KeyframeGraph& graph = mapper.graph();
  std::map<std::pair<std::uint32_t, std::uint64_t>, std::vector<std::uint32_t>> segments;
  for (const auto& [key, n] : graph.by_key()) {
    if (!map.fused_pose(n)) continue;
    segments[{graph.node(n).stream, key.id / static_cast<std::uint64_t>(segment_keyframes)}]
        .push_back(n);
  }
  std::map<TileKey, MapTile> tiles;
  for (const auto& [segment, nodes] : segments) {
    std::uint32_t reference = nodes.front();
    for (std::uint32_t n : nodes) {
      if (graph.node(n).key.id < graph.node(reference).key.id) reference = n;
    }
    const Eigen::Isometry3d frame = *map.fused_pose(reference);
    SegmentVoxels voxels;
    for (std::uint32_t n : nodes) {
      const Eigen::Isometry3d relative = frame.inverse(Eigen::Isometry) * *map.fused_pose(n);
      EXPECT_EQ(voxels.apply(*mapper.cache().get(graph.node(n).key), relative,
                             map.geometry().voxels.voxel_size, +1),
                0u);
    }
    std::map<TileKey, bool> seen;
    for (const FusedMoment& m : placed_moments(voxels, frame, map.geometry())) {
      MapTile& t = tiles.try_emplace(m.tile, m.tile).first->second;
      if (!seen[m.tile]) t.count_keyframe(static_cast<std::int64_t>(nodes.size()));
      seen[m.tile] = true;
      EXPECT_TRUE(t.apply(m.voxel, m.moments, +1));
    }
  }
  return tiles;
}

/// Count, sum of points and sum of their outer products (about the map origin) of the tiles.
struct Mass {
  double count = 0.0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d sum_sq = Eigen::Matrix3d::Zero();
};
Mass mass_of(const std::map<TileKey, MapTile>& tiles) {
  Mass m;
  for (const auto& [key, tile] : tiles) {
    for (const MapTile::Voxel& v : tile.voxels()) {
      const VoxelMoments about_origin = v.moments.transformed(
          Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
      m.count += about_origin.count;
      m.sum += about_origin.sum;
      m.sum_sq += about_origin.second_moment();
    }
  }
  return m;
}

void expect_same_distributions(const std::vector<Distribution>& a,
                               const std::vector<Distribution>& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].count, b[i].count) << what << " voxel " << i;
    EXPECT_LT((a[i].mean - b[i].mean).norm(), 1e-9) << what << " voxel " << i;
    EXPECT_LT((a[i].cov - b[i].cov).norm(), 1e-9) << what << " voxel " << i;
  }
}

void expect_equals_full_rebuild(const Mapper& mapper, TileMap& map, int segment_keyframes) {
  const std::map<TileKey, MapTile> full = segment_keyframes > 0
                                              ? segment_rebuild(mapper, map, segment_keyframes)
                                              : full_rebuild(mapper, map);
  ASSERT_EQ(map.index().size(), full.size());
  std::size_t distributions = 0;
  for (const auto& [key, tile] : full) {
    const auto incremental = map.tile(key);
    ASSERT_TRUE(incremental) << key.ix << "," << key.iy;
    EXPECT_EQ(incremental->keyframes(), tile.keyframes());
    EXPECT_EQ(incremental->voxels().size(), tile.voxels().size());
    const auto d = tile.distributions(map.geometry());
    expect_same_distributions(incremental->distributions(map.geometry()), d,
                              "tile " + std::to_string(key.ix) + "," + std::to_string(key.iy));
    const TileSummary& s = map.index().at(key);
    EXPECT_EQ(s.distributions, static_cast<std::int64_t>(d.size()));
    EXPECT_EQ(s.keyframes, tile.keyframes());
    distributions += d.size();
  }
  EXPECT_EQ(map.stats().distributions, distributions);
  EXPECT_EQ(map.stats().inconsistent, 0u);
}

/// Feeds the arrivals to a mapper, optimising as the aggregator does and marking what changed,
/// updating at most `budget` keyframes per step; a full pass at the end.
void run(Mapper& mapper, TileMap& map, std::size_t budget,
         const std::function<void(TileMap::Changes)>& persist = {}) {
  auto step = [&](std::size_t max) {
    for (std::uint32_t n : mapper.take_changed()) map.mark(n);
    map.update(mapper.graph(), mapper.cache(), max);
    if (persist) persist(map.take_changes());
  };
  for (const Keyframe& kf : arrivals()) {
    mapper.add_keyframe(kf);
    mapper.optimize();
    step(budget);
  }
  mapper.optimize_full();
  step(0);
}

}  // namespace

class MappingTileMapModes : public ::testing::TestWithParam<int> {};

TEST_P(MappingTileMapModes, IncrementalUpdatesEqualAFullRebuild) {
  Mapper mapper(street_config());
  TileMapConfig config;
  config.segment_keyframes = GetParam();
  config.tile_size = 20.0;  // the street spans several tiles
  // Thresholds below the loops' corrections of this short drive, so that many keyframes are
  // moved in the map (subtracted and added again), not only added.
  config.move_threshold_m = 0.05;
  config.move_threshold_deg = 0.05;
  TileMap map(config, mapper.config().map_voxel_size);
  run(mapper, map, 2);
  ASSERT_GT(mapper.loops().size(), 5u);
  EXPECT_EQ(mapper.map_anchor(), "a");
  EXPECT_EQ(mapper.pose({"b", 3})->frame, "a") << "b was not joined to the map";
  EXPECT_EQ(map.pending(), 0u);
  const TileMapStats s = map.stats();
  EXPECT_GT(s.tiles, 3u);
  // b's first keyframes were in the map before a came, then left it, then came back; a's
  // keyframes moved with the loops.
  EXPECT_GT(s.subtracted, 20u);
  EXPECT_GT(s.added, s.subtracted);
  if (config.segment_keyframes > 0) {
    EXPECT_GT(s.segments, 3u);
    // Segments were re-placed whole (frame moved), not only built.
    EXPECT_GT(s.segment_placements, 2 * s.segments);
  }
  expect_equals_full_rebuild(mapper, map, config.segment_keyframes);
}

TEST(MappingTileMap, SegmentsHoldTheMassOfTheKeyframesFusedOneByOne) {
  // A placed segment's count and first and second moments are its keyframes' at the same
  // poses (a rigid transform of every point); only the voxel a point lands in may differ.
  Mapper mapper(street_config());
  TileMapConfig config;
  config.tile_size = 20.0;
  config.move_threshold_m = 0.05;
  config.move_threshold_deg = 0.05;
  ASSERT_GT(config.segment_keyframes, 0) << "segments are the default";
  TileMap map(config, mapper.config().map_voxel_size);
  run(mapper, map, 2);
  std::map<TileKey, MapTile> incremental;
  for (const auto& [key, summary] : map.index()) incremental.emplace(key, *map.tile(key));
  const Mass a = mass_of(incremental);
  const Mass b = mass_of(full_rebuild(mapper, map));
  ASSERT_GT(b.count, 1000.0);
  EXPECT_EQ(a.count, b.count);
  EXPECT_LT((a.sum - b.sum).norm(), 1e-9 * b.sum.norm());
  EXPECT_LT((a.sum_sq - b.sum_sq).norm(), 1e-9 * b.sum_sq.norm());
}

TEST(MappingTileMap, EvictedSegmentsAreRecomputedToTheSameMap) {
  // A segment cache of 0 bytes: every segment's moments are recomputed from its keyframes
  // whenever it moves; the tiles come out as with the moments kept.
  Mapper a(street_config()), b(street_config());
  TileMapConfig config;
  config.tile_size = 20.0;
  config.move_threshold_m = 0.05;
  config.move_threshold_deg = 0.05;
  TileMap kept(config, a.config().map_voxel_size);
  config.segment_cache_mb = 0.0;
  TileMap recomputed(config, b.config().map_voxel_size);
  run(a, kept, 2);
  run(b, recomputed, 2);
  EXPECT_EQ(kept.stats().segment_recomputes, 0u);
  EXPECT_GT(recomputed.stats().segment_recomputes, 10u);
  EXPECT_EQ(recomputed.stats().segment_bytes, 0u);
  EXPECT_EQ(recomputed.stats().inconsistent, 0u);
  ASSERT_EQ(recomputed.index().size(), kept.index().size());
  for (const auto& [key, summary] : kept.index()) {
    expect_same_distributions(recomputed.tile(key)->distributions(recomputed.geometry()),
                              kept.tile(key)->distributions(kept.geometry()),
                              "tile " + std::to_string(key.ix) + "," + std::to_string(key.iy));
  }
  expect_equals_full_rebuild(b, recomputed, config.segment_keyframes);
}

TEST(MappingTileMap, SpilledSegmentsAreReadBackToTheSameMap) {
  // A segment cache of 0 bytes with a spill: every evicted segment's moments are written to the
  // spill and read back when the segment moves again, never recomputed; the tiles are bit for
  // bit those of a map that kept every segment's moments in memory (the same moments, added and
  // subtracted in the same order).
  Mapper a(street_config()), b(street_config());
  TileMapConfig config;
  config.tile_size = 20.0;
  config.move_threshold_m = 0.05;
  config.move_threshold_deg = 0.05;
  TileMap kept(config, a.config().map_voxel_size);
  config.segment_cache_mb = 0.0;
  TileMap spilled(config, b.config().map_voxel_size);
  const std::string path = ::testing::TempDir() + "tile_map_test-segments";
  spilled.spill_segments_to(std::make_unique<SegmentSpill>(path));
  run(a, kept, 2);
  run(b, spilled, 2);
  const TileMapStats s = spilled.stats();
  EXPECT_EQ(s.segment_recomputes, 0u);
  EXPECT_GT(s.segment_spill_reads, 10u);
  EXPECT_GE(s.segment_spill_writes, s.segment_spill_reads);
  EXPECT_GT(s.segment_spill_bytes, 0u);
  EXPECT_EQ(s.segment_bytes, 0u);
  EXPECT_EQ(s.inconsistent, 0u);
  EXPECT_EQ(s.segment_placements, kept.stats().segment_placements);
  ASSERT_EQ(spilled.index().size(), kept.index().size());
  for (const auto& [key, summary] : kept.index()) {
    const auto x = spilled.tile(key), y = kept.tile(key);
    ASSERT_EQ(x->voxels().size(), y->voxels().size());
    for (std::size_t i = 0; i < x->voxels().size(); ++i) {
      const VoxelMoments& p = x->voxels()[i].moments;
      const VoxelMoments& q = y->voxels()[i].moments;
      EXPECT_EQ(x->voxels()[i].key, y->voxels()[i].key);
      EXPECT_EQ(p.count, q.count);
      EXPECT_EQ(p.sum, q.sum);
      EXPECT_EQ(p.sum_sq, q.sum_sq);
    }
  }
  expect_equals_full_rebuild(b, spilled, config.segment_keyframes);
}

TEST_P(MappingTileMapModes, EvictedTilesReadBackGiveTheSameMap) {
  Mapper a(street_config()), b(street_config());
  TileMapConfig config;
  config.segment_keyframes = GetParam();
  config.tile_size = 20.0;
  TileMap unbounded(config, a.config().map_voxel_size);
  std::map<TileKey, MapTile> persisted;
  std::size_t loads = 0;
  TileMap bounded(
      config, b.config().map_voxel_size,
      [&](TileKey key) -> std::optional<MapTile> {
        ++loads;
        const auto it = persisted.find(key);
        if (it == persisted.end()) return std::nullopt;
        return it->second;
      },
      1);
  run(a, unbounded, 3);
  run(b, bounded, 3, [&](TileMap::Changes changes) {
    for (const auto& t : changes.tiles) {
      if (t->empty())
        persisted.erase(t->key());
      else
        persisted.insert_or_assign(t->key(), *t);
    }
  });
  EXPECT_GT(loads, 10u) << "the cache was not exercised";
  EXPECT_LE(bounded.stats().tiles_in_memory, 1u);
  ASSERT_EQ(bounded.index().size(), unbounded.index().size());
  for (const auto& [key, summary] : unbounded.index()) {
    expect_same_distributions(bounded.tile(key)->distributions(bounded.geometry()),
                              unbounded.tile(key)->distributions(unbounded.geometry()),
                              "tile " + std::to_string(key.ix) + "," + std::to_string(key.iy));
  }
}

TEST(MappingTileMap, WithoutMoveThresholdTilesHoldTheGlobalMap) {
  Mapper mapper(street_config());
  TileMapConfig config;
  config.segment_keyframes = 0;  // keyframe by keyframe: the global map's voxels exactly
  config.tile_size = 20.0;
  config.move_threshold_m = 0.0;
  config.move_threshold_deg = 0.0;
  TileMap map(config, mapper.config().map_voxel_size);
  run(mapper, map, 0);
  // The global map's distributions by voxel, against the tiles'.
  const double inv = 1.0 / mapper.config().map_voxel_size;
  std::map<std::uint64_t, Distribution> global;
  for (const Distribution& d : mapper.global_map())
    global[pack_voxel(voxel_index(d.mean, inv))] = d;
  std::size_t tiled = 0;
  for (const auto& [key, summary] : map.index()) {
    for (const Distribution& d : map.tile(key)->distributions(map.geometry())) {
      const auto it = global.find(pack_voxel(voxel_index(d.mean, inv)));
      ASSERT_NE(it, global.end());
      EXPECT_EQ(it->second.count, d.count);
      EXPECT_LT((it->second.mean - d.mean).norm(), 1e-9);
      EXPECT_LT((it->second.cov - d.cov).norm(), 1e-9);
      ++tiled;
    }
  }
  EXPECT_EQ(tiled, global.size());
  EXPECT_GT(tiled, 100u);
}

TEST_P(MappingTileMapModes, KeyframesStayFusedWithinTheMoveThresholdOfTheirPoses) {
  // The default thresholds (0.3 m, 0.3 degrees): moves below them leave a keyframe fused
  // where it was, so the map differs from one fused at the current poses by at most that;
  // every keyframe in the map is within it after the updates, and the loops' corrections
  // (larger) were fused.
  Mapper mapper(street_config());
  TileMapConfig config;
  config.segment_keyframes = GetParam();
  config.tile_size = 20.0;
  TileMap map(config, mapper.config().map_voxel_size);
  run(mapper, map, 2);
  ASSERT_EQ(map.pending(), 0u);
  std::size_t in_map = 0;
  for (std::uint32_t n = 0; n < mapper.graph().size(); ++n) {
    const auto fused = map.fused_pose(n);
    if (!fused) continue;
    ++in_map;
    const Eigen::Isometry3d& pose = mapper.graph().node(n).pose;
    EXPECT_LE((fused->translation() - pose.translation()).norm(), config.move_threshold_m);
    EXPECT_LE(Eigen::AngleAxisd(fused->linear().transpose() * pose.linear()).angle(),
              config.move_threshold_deg * M_PI / 180.0 + 1e-12);
  }
  EXPECT_EQ(in_map, mapper.graph().size());
  EXPECT_GT(map.stats().subtracted + map.stats().segment_placements, 0u);
  expect_equals_full_rebuild(mapper, map, config.segment_keyframes);
}

TEST(MappingTileMap, AMoveThresholdOfAVoxelOrMoreIsRejected) {
  TileMapConfig config;
  config.move_threshold_m = 3.0;
  EXPECT_THROW(TileMap(config, 3.0), ConfigError);
  config.move_threshold_m = 2.9;
  EXPECT_NO_THROW(TileMap(config, 3.0));
  config.move_threshold_deg = -1.0;
  EXPECT_THROW(TileMap(config, 3.0), ConfigError);
  config.move_threshold_deg = 0.3;
  config.segment_keyframes = -1;
  EXPECT_THROW(TileMap(config, 3.0), ConfigError);
  config.segment_keyframes = 10;
  config.segment_cache_mb = -1.0;
  EXPECT_THROW(TileMap(config, 3.0), ConfigError);
}

// 0: keyframe by keyframe; 4: segments (the street drive has ~40 keyframes a stream).
INSTANTIATE_TEST_SUITE_P(KeyframesAndSegments, MappingTileMapModes, ::testing::Values(0, 4));

// A tile full of voxels (a 100 m tile of 3 m voxels, 8 high: 9,248) keeps an index of the
// order of its voxels: the packed key's low bits are the x index alone, and an index that
// hashed it as is (robin_map's power-of-two buckets) put each x column in one bucket run and
// grew to 4 million buckets (64 MB, ~1000x slower lookups). Every voxel is found again.
TEST(MappingTileMap, ADenseTileKeepsItsIndexSmall) {
  MapTile tile(TileKey{0, 0});
  std::vector<std::uint64_t> keys;
  for (int x = 0; x < 34; ++x)
    for (int y = 0; y < 34; ++y)
      for (int z = -3; z < 5; ++z) keys.push_back(pack_voxel(VoxelIndex(x + 340, y - 500, z)));
  VoxelMoments one;
  one.count = 1;
  for (std::uint64_t key : keys) ASSERT_TRUE(tile.apply(key, one, +1));
  ASSERT_EQ(tile.voxels().size(), keys.size());
  const std::size_t voxel_bytes = keys.size() * sizeof(MapTile::Voxel);
  EXPECT_LT(tile.bytes(), 2 * voxel_bytes + voxel_bytes / 2) << "the index outgrew the voxels";
  const MapTile restored = MapTile::restore(TileKey{0, 0}, 0, tile.voxels());
  EXPECT_LT(restored.bytes(), 2 * voxel_bytes + voxel_bytes / 2);
  for (std::uint64_t key : keys) ASSERT_TRUE(tile.apply(key, one, -1));
  EXPECT_TRUE(tile.empty());
}

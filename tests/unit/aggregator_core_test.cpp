// The aggregator core with a distribution cache too small to hold anything but the latest
// keyframe (every verification re-reads its submap from the store) finds the same loops and
// poses, bit for bit, as with every keyframe in memory; reopened, it recovers the same graph
// from its tables, with its map tiles, and finishes a tile update it had stopped half way.

#include "litamin2/aggregator/aggregator_core.hpp"
#include "litamin2/aggregator/map_export.hpp"
#include "support/process_temp_dir.hpp"
#include "support/street_drive.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <tuple>

using namespace litamin2;
using namespace litamin2::aggregator;
using litamin2::testing::drive;
using litamin2::testing::out_and_back;

namespace {

std::string fresh_store(const std::string& name) {
  return litamin2::testing::fresh_store_path("litamin2_core_test_", name);
}

mapping::MapperConfig street_config() {
  mapping::MapperConfig config;
  config.place.min_travel_gap = 20.0;
  return config;
}

void feed(AggregatorCore& core, const std::vector<Keyframe>& keyframes) {
  for (std::size_t i = 0; i < keyframes.size(); i += 5) {
    std::vector<Keyframe> batch(
        keyframes.begin() + static_cast<std::ptrdiff_t>(i),
        keyframes.begin() + static_cast<std::ptrdiff_t>(std::min(i + 5, keyframes.size())));
    core.ingest(batch);
  }
}

void expect_same(const mapping::Mapper& a, const mapping::Mapper& b) {
  ASSERT_EQ(a.loops().size(), b.loops().size());
  for (std::size_t i = 0; i < a.loops().size(); ++i) {
    EXPECT_EQ(a.loops()[i].to, b.loops()[i].to);
    EXPECT_TRUE(a.loops()[i].relative.matrix() == b.loops()[i].relative.matrix()) << i;
  }
  const auto pa = a.poses(), pb = b.poses();
  ASSERT_EQ(pa.size(), pb.size());
  for (std::size_t i = 0; i < pa.size(); ++i) {
    EXPECT_EQ(pa[i].key, pb[i].key);
    EXPECT_EQ(pa[i].frame, pb[i].frame);
    EXPECT_TRUE(pa[i].pose.matrix() == pb[i].pose.matrix()) << pa[i].key.id;
  }
}

}  // namespace

TEST(AggregatorCore, CacheEvictionAndReReadGiveIdenticalRegistrations) {
  const auto keyframes = drive("a", out_and_back(), 0.05, 1);
  CoreOptions all_in_memory, tiny;
  all_in_memory.distribution_cache_bytes = 0;
  tiny.distribution_cache_bytes = 1;
  AggregatorCore a(fresh_store("a.db"), store::OpenMode::kCreateIfMissing, street_config(), {}, {},
                   all_in_memory);
  AggregatorCore b(fresh_store("b.db"), store::OpenMode::kCreateIfMissing, street_config(), {}, {},
                   tiny);
  feed(a, keyframes);
  feed(b, keyframes);
  EXPECT_GT(a.mapper().loops().size(), 5u);
  EXPECT_GT(b.mapper().cache().stats().misses, 20u) << "the cache was not exercised";
  EXPECT_LE(b.mapper().cache().stats().entries, 1u);
  expect_same(a.mapper(), b.mapper());
}

TEST(AggregatorCore, ReopenedRecoversTheSameGraphFromItsTables) {
  const auto truth = out_and_back();
  const auto a = drive("a", {truth.begin(), truth.begin() + 21}, 0.0, 1);
  const auto b = drive("b", {truth.begin() + 21, truth.end()}, 0.0, 2);
  const std::string path = fresh_store("reopen.db");
  std::vector<Keyframe> all = a;
  all.insert(all.end(), b.begin(), b.end());
  {
    AggregatorCore core(path, store::OpenMode::kCreateIfMissing, street_config());
    feed(core, all);
    ASSERT_FALSE(core.mapper().loops().empty());
    AggregatorCore reopened(path, store::OpenMode::kReadOnly, street_config());
    expect_same(core.mapper(), reopened.mapper());
    EXPECT_EQ(reopened.mapper().map_anchor(), core.mapper().map_anchor());
  }
}

namespace {

/// Every distribution of the map, tile by tile, as (tile, mean, count).
std::vector<std::tuple<mapping::TileKey, Eigen::Vector3d, int>> map_of(AggregatorCore& core) {
  std::vector<std::tuple<mapping::TileKey, Eigen::Vector3d, int>> out;
  mapping::TileMap& tiles = core.tiles();
  for (const auto& [key, summary] : tiles.index()) {
    for (const Distribution& d : tiles.tile(key)->distributions(tiles.geometry()))
      out.emplace_back(key, d.mean, d.count);
  }
  return out;
}

}  // namespace

TEST(AggregatorCore, ReopenedRecoversTheCommittedTilesAndFusesTheRest) {
  const auto keyframes = drive("a", out_and_back(), 0.0, 1);
  CoreOptions options;
  options.tiles.tile_size = 20.0;  // several tiles on the drive
  const std::string path = fresh_store("tiles.db");
  std::vector<std::tuple<mapping::TileKey, Eigen::Vector3d, int>> expected;
  std::size_t left = 0;
  {
    AggregatorCore core(path, store::OpenMode::kCreateIfMissing, street_config(), {}, {}, options);
    feed(core, keyframes);
    ASSERT_GT(core.map_pending(), 10u);
    // Half the keyframes fused and committed: the rest stays marked in the store.
    const MapUpdate u = core.update_map(core.map_pending() / 2);
    EXPECT_FALSE(u.tiles.empty());
    left = core.map_pending();
    ASSERT_GT(left, 0u);
    EXPECT_EQ(core.store().tile_count(), core.tiles().index().size());
    core.update_map(0);
    EXPECT_EQ(core.map_pending(), 0u);
    expected = map_of(core);
  }
  ASSERT_GT(expected.size(), 100u);
  {
    AggregatorCore reopened(path, store::OpenMode::kReadOnly, street_config(), {}, {}, options);
    EXPECT_EQ(reopened.map_pending(), 0u);
    const auto got = map_of(reopened);
    ASSERT_EQ(got.size(), expected.size());
    for (std::size_t i = 0; i < got.size(); ++i) {
      EXPECT_EQ(std::get<0>(got[i]), std::get<0>(expected[i]));
      EXPECT_LT((std::get<1>(got[i]) - std::get<1>(expected[i])).norm(), 1e-6) << i;
      EXPECT_EQ(std::get<2>(got[i]), std::get<2>(expected[i]));
    }
  }
}

TEST(AggregatorCore, ATileUpdateStoppedHalfWayIsFinishedAfterAReopen) {
  const auto keyframes = drive("a", out_and_back(), 0.0, 1);
  CoreOptions options;
  options.tiles.tile_size = 20.0;
  const std::string full_path = fresh_store("tiles_full.db");
  const std::string half_path = fresh_store("tiles_half.db");
  std::vector<std::tuple<mapping::TileKey, Eigen::Vector3d, int>> expected;
  {
    AggregatorCore core(full_path, store::OpenMode::kCreateIfMissing, street_config(), {}, {},
                        options);
    feed(core, keyframes);
    core.update_map(0);
    expected = map_of(core);
  }
  std::size_t left = 0;
  {
    AggregatorCore core(half_path, store::OpenMode::kCreateIfMissing, street_config(), {}, {},
                        options);
    feed(core, keyframes);
    core.update_map(core.map_pending() / 3);
    left = core.map_pending();
  }
  ASSERT_GT(left, 0u);
  AggregatorCore reopened(half_path, store::OpenMode::kMustExist, street_config(), {}, {}, options);
  EXPECT_EQ(reopened.map_pending(), left);
  reopened.update_map(0);
  const auto got = map_of(reopened);
  ASSERT_EQ(got.size(), expected.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(std::get<0>(got[i]), std::get<0>(expected[i]));
    EXPECT_LT((std::get<1>(got[i]) - std::get<1>(expected[i])).norm(), 1e-6) << i;
    EXPECT_EQ(std::get<2>(got[i]), std::get<2>(expected[i]));
  }
}

namespace {

void expect_same_map(const std::vector<std::tuple<mapping::TileKey, Eigen::Vector3d, int>>& got,
                     const std::vector<std::tuple<mapping::TileKey, Eigen::Vector3d, int>>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(std::get<0>(got[i]), std::get<0>(want[i]));
    EXPECT_LT((std::get<1>(got[i]) - std::get<1>(want[i])).norm(), 1e-6) << i;
    EXPECT_EQ(std::get<2>(got[i]), std::get<2>(want[i]));
  }
}

}  // namespace

// map_tiles.persist_period_s: updates without persist change the tiles in memory only (and
// say which tiles changed, to publish); the store keeps the last persisted tiles with the
// poses they were fused at, so a core dropped before persisting (kill -9) fuses everything
// again on reopen, and one persisted after deferred updates reopens where it was. Both end
// with the map of a core that stored every update.
TEST(AggregatorCore, DeferredTileStoresKeepTheStoreConsistent) {
  const auto keyframes = drive("a", out_and_back(), 0.0, 1);
  CoreOptions options;
  options.tiles.tile_size = 20.0;
  std::vector<std::tuple<mapping::TileKey, Eigen::Vector3d, int>> expected;
  std::size_t all = 0;
  {
    AggregatorCore core(fresh_store("persist_every.db"), store::OpenMode::kCreateIfMissing,
                        street_config(), {}, {}, options);
    feed(core, keyframes);
    all = core.map_pending();
    core.update_map(all / 3);
    core.update_map(all / 3);
    core.update_map(0);
    expected = map_of(core);
  }
  ASSERT_GT(expected.size(), 100u);

  const std::string dropped = fresh_store("persist_dropped.db");
  {
    AggregatorCore core(dropped, store::OpenMode::kCreateIfMissing, street_config(), {}, {},
                        options);
    feed(core, keyframes);
    ASSERT_EQ(core.map_pending(), all);
    const MapUpdate u = core.update_map(all / 3, false);
    EXPECT_FALSE(u.tiles.empty());
    EXPECT_TRUE(std::is_sorted(u.tiles.begin(), u.tiles.end()));
    EXPECT_TRUE(core.map_unsaved());
    EXPECT_EQ(core.store().tile_count(), 0u);
    core.update_map(all / 3, false);
    EXPECT_EQ(core.store().tile_count(), 0u);
    EXPECT_LT(core.map_pending(), all);
  }  // dropped without persisting
  {
    AggregatorCore reopened(dropped, store::OpenMode::kMustExist, street_config(), {}, {}, options);
    EXPECT_EQ(reopened.map_pending(), all);
    reopened.update_map(0);
    expect_same_map(map_of(reopened), expected);
  }

  const std::string persisted = fresh_store("persist_later.db");
  std::size_t left = 0;
  {
    AggregatorCore core(persisted, store::OpenMode::kCreateIfMissing, street_config(), {}, {},
                        options);
    feed(core, keyframes);
    core.update_map(all / 3, false);
    core.update_map(all / 3, true);
    EXPECT_FALSE(core.map_unsaved());
    EXPECT_EQ(core.store().tile_count(), core.tiles().index().size());
    left = core.map_pending();
    core.update_map(all / 3, false);  // not persisted: fused again after the reopen
  }
  ASSERT_GT(left, 0u);
  AggregatorCore reopened(persisted, store::OpenMode::kMustExist, street_config(), {}, {}, options);
  EXPECT_EQ(reopened.map_pending(), left);
  reopened.update_map(0);
  expect_same_map(map_of(reopened), expected);
}

TEST(AggregatorCore, TheMapInABoxIsTheWholeMapCutToTheBoxReadFromTheTilesThatMeetIt) {
  const auto keyframes = drive("a", out_and_back(), 0.0, 1);
  CoreOptions options;
  options.tiles.tile_size = 20.0;
  AggregatorCore core(fresh_store("box.db"), store::OpenMode::kCreateIfMissing, street_config(), {},
                      {}, options);
  feed(core, keyframes);
  core.update_map(0);
  std::size_t all_tiles = 0, box_tiles = 0;
  const std::vector<Distribution> all = map_in_box(core.tiles(), std::nullopt, &all_tiles);
  ASSERT_GT(all_tiles, 2u);
  // A box around the middle of the map's extent.
  Eigen::Vector3d lo = all.front().mean, hi = all.front().mean;
  for (const Distribution& d : all) {
    lo = lo.cwiseMin(d.mean);
    hi = hi.cwiseMax(d.mean);
  }
  const Eigen::Vector3d mid = 0.5 * (lo + hi), half = 0.2 * (hi - lo);
  ExportOptions::Box box{mid.x() - half.x(), mid.y() - half.y(), mid.x() + half.x(),
                         mid.y() + half.y()};
  const std::vector<Distribution> cut = map_in_box(core.tiles(), box, &box_tiles);
  EXPECT_LT(box_tiles, all_tiles);
  std::size_t inside = 0;
  for (const Distribution& d : all) {
    if (d.mean.x() >= box.min_x && d.mean.x() <= box.max_x && d.mean.y() >= box.min_y &&
        d.mean.y() <= box.max_y)
      ++inside;
  }
  EXPECT_GT(inside, 0u);
  EXPECT_LT(inside, all.size());
  EXPECT_EQ(cut.size(), inside);
  for (const Distribution& d : cut) {
    EXPECT_GE(d.mean.x(), box.min_x);
    EXPECT_LE(d.mean.x(), box.max_x);
    EXPECT_GE(d.mean.y(), box.min_y);
    EXPECT_LE(d.mean.y(), box.max_y);
  }
}

TEST(AggregatorCore, AReopenedStoreKeepsTheLoopsWaitingForAMergesConfirmation) {
  // Two vehicles that meet: the first verified loop between them waits for a second agreeing
  // one (merge_confirmation.hpp). The store is closed right after it (as a kill -9 would: every
  // batch is committed) and reopened: the waiting loop is there, and the rest of the drive
  // merges the two frames with the same loops as an uninterrupted run.
  mapping::MapperConfig config = street_config();
  // As mapping_mapper_test's TwoVehicles: b drives the street back later, from its far end
  // (its frame 60 m and 180 degrees from a's); they find each other over 18 m of it.
  config.place.merge_min_separation = 10.0;
  const auto truth = out_and_back();
  const auto a = drive("a", {truth.begin(), truth.begin() + 21}, 0.0, 1);
  auto b = drive("b", {truth.begin() + 21, truth.end()}, 0.0, 2);
  for (auto& kf : b) kf.stamp.nanoseconds += 1000000000;
  std::vector<Keyframe> all = a;
  all.insert(all.end(), b.begin(), b.end());
  const std::string uninterrupted_path = fresh_store("pending_uninterrupted.db");
  const std::string path = fresh_store("pending.db");
  AggregatorCore uninterrupted(uninterrupted_path, store::OpenMode::kCreateIfMissing, config);
  std::vector<mapping::LoopEdge> pending;
  std::size_t fed = 0;
  {
    AggregatorCore core(path, store::OpenMode::kCreateIfMissing, config);
    for (; fed < all.size() && pending.empty(); ++fed) {
      std::vector<Keyframe> one{all[fed]}, same{all[fed]};
      core.ingest(one);
      uninterrupted.ingest(same);
      pending = core.mapper().pending_merges();
    }
    ASSERT_FALSE(pending.empty()) << "no loop between the vehicles waited for a confirmation";
    EXPECT_NE(core.mapper().pose({"b", 0})->frame, "a");
  }
  AggregatorCore reopened(path, store::OpenMode::kMustExist, config);
  const std::vector<mapping::LoopEdge> restored = reopened.mapper().pending_merges();
  ASSERT_EQ(restored.size(), pending.size());
  for (std::size_t i = 0; i < pending.size(); ++i) {
    EXPECT_EQ(restored[i].from, pending[i].from);
    EXPECT_EQ(restored[i].to, pending[i].to);
    EXPECT_TRUE(restored[i].relative.matrix() == pending[i].relative.matrix());
    EXPECT_TRUE(restored[i].information == pending[i].information);
    EXPECT_EQ(restored[i].fitness, pending[i].fitness);
  }
  for (; fed < all.size(); ++fed) {
    std::vector<Keyframe> one{all[fed]}, same{all[fed]};
    reopened.ingest(one);
    uninterrupted.ingest(same);
  }
  EXPECT_EQ(uninterrupted.mapper().pose({"b", 0})->frame, "a") << "the vehicles never merged";
  EXPECT_EQ(reopened.mapper().pose({"b", 0})->frame, "a");
  EXPECT_EQ(reopened.mapper().loops().size(), uninterrupted.mapper().loops().size());
}

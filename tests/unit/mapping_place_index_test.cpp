// The place search through its indexes (ring-key kd-tree, spatial grid) gives the linear
// scan's candidates: on the street drives (same loops, bit-identical poses) and, candidate by
// candidate, on random ring keys with ties and ineligible nodes.

#include "litamin2/mapping/keyframe_graph.hpp"
#include "litamin2/mapping/loop_detector.hpp"
#include "litamin2/mapping/mapper.hpp"
#include "litamin2/mapping/ring_key_index.hpp"
#include "litamin2/mapping/spatial_grid.hpp"
#include "support/street_drive.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <map>
#include <random>
#include <set>

using namespace litamin2;
using namespace litamin2::mapping;
using litamin2::testing::drive;
using litamin2::testing::out_and_back;

namespace {

MapperConfig config_with(PlaceSearch search) {
  MapperConfig config;
  config.place.min_travel_gap = 20.0;
  config.place.search = search;
  return config;
}

void expect_same_mapping(const Mapper& indexed, const Mapper& linear) {
  ASSERT_EQ(indexed.loops().size(), linear.loops().size());
  for (std::size_t i = 0; i < indexed.loops().size(); ++i) {
    EXPECT_EQ(indexed.loops()[i].from, linear.loops()[i].from) << i;
    EXPECT_EQ(indexed.loops()[i].to, linear.loops()[i].to) << i;
    EXPECT_TRUE(indexed.loops()[i].relative.matrix() == linear.loops()[i].relative.matrix()) << i;
  }
  EXPECT_EQ(indexed.stats().candidates, linear.stats().candidates);
  const auto a = indexed.poses(), b = linear.poses();
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_TRUE(a[i].pose.matrix() == b[i].pose.matrix());
}

}  // namespace

TEST(MappingPlaceIndex, SameLoopsAsTheLinearScanOnADrivingLoop) {
  const auto keyframes = drive("a", out_and_back(), 0.05, 1);
  Mapper indexed(config_with(PlaceSearch::kIndexed)), linear(config_with(PlaceSearch::kLinear));
  for (const auto& kf : keyframes) {
    indexed.add_keyframe(kf);
    linear.add_keyframe(kf);
    indexed.optimize();
    linear.optimize();
  }
  EXPECT_GT(indexed.loops().size(), 5u);
  expect_same_mapping(indexed, linear);
}

TEST(MappingPlaceIndex, SameLoopsAsTheLinearScanBetweenTwoVehicles) {
  const auto truth = out_and_back();
  const auto a = drive("a", {truth.begin(), truth.begin() + 21}, 0.0, 1);
  const auto b = drive("b", {truth.begin() + 21, truth.end()}, 0.0, 2);
  Mapper indexed(config_with(PlaceSearch::kIndexed)), linear(config_with(PlaceSearch::kLinear));
  for (const std::vector<Keyframe>* stream : {&a, &b}) {
    for (const auto& kf : *stream) {
      indexed.add_keyframe(kf);
      linear.add_keyframe(kf);
    }
  }
  indexed.optimize();
  linear.optimize();
  EXPECT_FALSE(indexed.loops().empty());
  expect_same_mapping(indexed, linear);
}

TEST(MappingPlaceIndex, RingKeyShortlistEqualsTheLinearOneWithTiesAndIneligibleNodes) {
  // Keys of multiples of 1/8: many exact ties, broken by node number as the caller asks.
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> level(0, 8);
  const int dims = 6;
  RingKeyIndex index(dims);
  std::vector<std::vector<float>> keys;
  for (int i = 0; i < 3000; ++i) {
    std::vector<float> k(dims);
    for (float& v : k) v = static_cast<float>(level(rng)) / 8.0f;
    index.add(k);
    keys.push_back(k);
  }
  auto before = [](std::uint32_t a, std::uint32_t b) { return a > b; };  // any strict order
  for (int q = 0; q < 200; ++q) {
    std::vector<float> query(dims);
    for (float& v : query) v = static_cast<float>(level(rng)) / 8.0f;
    auto eligible = [&](std::uint32_t n) { return n % 7 != static_cast<std::uint32_t>(q % 7); };
    std::vector<std::pair<double, std::uint32_t>> all;
    for (std::uint32_t n = 0; n < keys.size(); ++n) {
      if (!eligible(n)) continue;
      all.emplace_back(index.distance(query, n), n);
    }
    std::sort(all.begin(), all.end(), [&](const auto& x, const auto& y) {
      return x.first < y.first || (x.first == y.first && before(x.second, y.second));
    });
    const std::vector<std::uint32_t> found = index.nearest(query, 10, eligible, before);
    ASSERT_EQ(found.size(), 10u);
    for (std::size_t i = 0; i < found.size(); ++i)
      EXPECT_EQ(found[i], all[i].second) << q << " " << i;
  }
}

TEST(MappingPlaceIndex, SpatialGridVisitsEveryNodeWithinTheRadiusAfterMoves) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-200.0, 200.0);
  SpatialGrid grid(30.0);
  std::vector<Eigen::Vector3d> at;
  for (std::uint32_t n = 0; n < 2000; ++n) {
    at.emplace_back(u(rng), u(rng), 0.0);
    grid.add(n, at.back());
  }
  for (std::uint32_t n = 0; n < 2000; n += 3) {
    at[n] = Eigen::Vector3d(u(rng), u(rng), 1.0);
    grid.move(n, at[n]);
  }
  for (int q = 0; q < 100; ++q) {
    const Eigen::Vector3d p(u(rng), u(rng), 0.0);
    std::set<std::uint32_t> visited;
    grid.visit_nearest_first(
        p, 30.0, 0, [&](std::uint32_t n) { EXPECT_TRUE(visited.insert(n).second); },
        [] { return std::numeric_limits<double>::infinity(); });
    for (std::uint32_t n = 0; n < at.size(); ++n) {
      if ((at[n] - p).norm() < 30.0) {
        EXPECT_TRUE(visited.count(n)) << n;
      }
    }
  }
}

TEST(MappingPlaceIndex, SameLoopsWithTheDescriptorCellsReadBackFromOutsideTheGraph) {
  // The aggregator keeps the cells in its store (Mapper::keep_descriptor_cells_outside): the
  // nodes hold ring keys only and a search reads its shortlist's cells back. Two vehicles, so
  // that the loops between them come from the descriptors' candidates.
  const auto truth = out_and_back();
  const auto a = drive("a", {truth.begin(), truth.begin() + 21}, 0.0, 1);
  const auto b = drive("b", {truth.begin() + 21, truth.end()}, 0.0, 2);
  Mapper outside(config_with(PlaceSearch::kIndexed)), inside(config_with(PlaceSearch::kIndexed));
  std::map<KeyframeKey, PlaceDescriptor> kept;  // the store's place
  std::size_t reads = 0;
  outside.keep_descriptor_cells_outside([&](const KeyframeKey& key) {
    ++reads;
    return kept.at(key);
  });
  for (const std::vector<Keyframe>* stream : {&a, &b}) {
    for (const auto& kf : *stream) {
      const PlaceDescriptor d = outside.describe(kf.distributions);
      kept[kf.key] = d;
      outside.add_keyframe(kf, nullptr, &d);
      inside.add_keyframe(kf);
      outside.optimize();
      inside.optimize();
    }
  }
  EXPECT_FALSE(outside.loops().empty());
  expect_same_mapping(outside, inside);
  EXPECT_GT(reads, 0u);
  EXPECT_EQ(outside.descriptor_loads(), reads);
  for (const KeyframeNode& n : outside.graph().nodes()) {
    EXPECT_TRUE(n.descriptor.cells.empty());
    EXPECT_EQ(n.descriptor.ring_key, kept.at(n.key).ring_key);
  }
  for (const KeyframeNode& n : inside.graph().nodes()) EXPECT_FALSE(n.descriptor.cells.empty());
}

TEST(MappingPlaceIndex, SpatialGridNearestFirstFindsTheNearestNodeWithoutVisitingTheWholeDisc) {
  // Dense enough that the nearest node is in the query's cell or the next ring: the search
  // must stop there and still return the brute-force nearest (ties by node number).
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-100.0, 100.0);
  SpatialGrid grid(5.0);
  std::vector<Eigen::Vector3d> at;
  for (std::uint32_t n = 0; n < 4000; ++n) {
    at.emplace_back(std::round(u(rng)), std::round(u(rng)), 0.0);  // many equal distances
    grid.add(n, at.back());
  }
  for (std::uint32_t n = 0; n < 4000; n += 5) {
    at[n] = Eigen::Vector3d(std::round(u(rng)), std::round(u(rng)), 0.0);
    grid.move(n, at[n]);
  }
  std::size_t visits = 0, in_disc = 0;
  for (int q = 0; q < 300; ++q) {
    const Eigen::Vector3d p(std::round(u(rng)), std::round(u(rng)) + 0.5, 0.0);
    std::int64_t expected = -1;
    double expected_sq = 30.0 * 30.0;
    for (std::uint32_t n = 0; n < at.size(); ++n) {
      const double d_sq = (at[n] - p).squaredNorm();
      if (d_sq < 30.0 * 30.0) ++in_disc;
      if (d_sq < expected_sq || (d_sq == expected_sq && expected >= 0 && n < expected)) {
        expected_sq = d_sq;
        expected = n;
      }
    }
    std::int64_t best = -1;
    double best_sq = 30.0 * 30.0;
    grid.visit_nearest_first(
        p, 30.0, 0,
        [&](std::uint32_t n) {
          ++visits;
          const double d_sq = (at[n] - p).squaredNorm();
          if (d_sq < best_sq || (d_sq == best_sq && best >= 0 && n < best)) {
            best_sq = d_sq;
            best = n;
          }
        },
        [&] { return best_sq; });
    EXPECT_EQ(best, expected) << q;
  }
  EXPECT_LT(visits * 5, in_disc);  // the early stop: a fraction of the disc's nodes
}

TEST(MappingPlaceIndex, SpatialGridLooksAtTheLatestNodesOfACellOnlyWhenAsked) {
  SpatialGrid grid(5.0);
  const Eigen::Vector3d here(1.0, 1.0, 0.0), there(101.0, 1.0, 0.0);
  for (std::uint32_t n = 0; n < 100; ++n) grid.add(n, here);
  // Out and back again: a node re-filed in its cell keeps its place in the arrival order.
  for (std::uint32_t n : {99u, 97u, 50u}) grid.move(n, there);
  for (std::uint32_t n : {97u, 50u}) grid.move(n, here);
  auto visited = [&](std::size_t per_cell) {
    std::vector<std::uint32_t> out;
    grid.visit_nearest_first(
        here, 2.0, per_cell, [&](std::uint32_t n) { out.push_back(n); },
        [] { return std::numeric_limits<double>::infinity(); });
    std::sort(out.begin(), out.end());
    return out;
  };
  EXPECT_EQ(visited(4), (std::vector<std::uint32_t>{95, 96, 97, 98}));
  EXPECT_EQ(visited(0).size(), 99u);
  EXPECT_EQ(visited(200).size(), 99u);
}

TEST(MappingPlaceIndex, DescriptorsAreSearchedOnlyWhenTheProximityCandidateFails) {
  // Every keyframe is searched (no spacing): each search is either closed by its proximity
  // candidate or goes on to the descriptors, never both.
  const auto keyframes = drive("a", out_and_back(), 0.05, 1);
  MapperConfig config = config_with(PlaceSearch::kIndexed);
  Mapper by_position(config);
  config.place.proximity_radius = 0.0;
  Mapper by_descriptor(config);
  for (const auto& kf : keyframes) {
    by_position.add_keyframe(kf);
    by_descriptor.add_keyframe(kf);
    by_position.optimize();
    by_descriptor.optimize();
  }
  const MapperStats& p = by_position.stats();
  EXPECT_GT(p.proximity_verified, 5u);
  EXPECT_EQ(p.descriptor_searches + p.proximity_verified, p.keyframes);
  EXPECT_EQ(by_descriptor.stats().descriptor_searches, by_descriptor.stats().keyframes);
  EXPECT_FALSE(by_descriptor.loops().empty());
}

TEST(MappingPlaceIndex, ProximityPrefersAStreamNotLoopedWithRecently) {
  // Three streams of one group along a street: the query (stream "q") has keyframes of "near"
  // 1 m away and of "far" 4 m away. Its stream looped with "near" recently: the candidate is
  // "far"'s keyframe, unless every stream within the radius is a recent partner.
  for (PlaceSearch search : {PlaceSearch::kIndexed, PlaceSearch::kLinear}) {
    MapperConfig config = config_with(search);
    KeyframeGraph graph(config.place.rings, config.place.proximity_cell_size);
    auto add = [&](const std::string& stream, std::uint64_t id, double x, double y) {
      KeyframeNode node;
      node.key = {stream, id};
      node.pose.translation() = Eigen::Vector3d(x, y, 0.0);
      return graph.add(node);
    };
    for (std::uint64_t id = 0; id < 5; ++id) add("near", id, 100.0 + 2.0 * id, 1.0);
    for (std::uint64_t id = 0; id < 5; ++id) add("far", id, 100.0 + 2.0 * id, 4.0);
    const std::uint32_t query = add("q", 0, 104.0, 0.0);
    StreamGroups& groups = graph.groups();
    groups.join(groups.index("near"), groups.index("far"));
    groups.join(groups.index("near"), groups.index("q"));
    const LoopDetector detector(config);
    const std::uint32_t near = groups.index("near"), far = groups.index("far");

    bool new_partner = true;
    auto c = detector.proximity_candidate(query, graph, {}, &new_partner);
    ASSERT_TRUE(c);
    EXPECT_EQ(graph.node(c->node).key, (KeyframeKey{"near", 2}));
    EXPECT_FALSE(new_partner);

    c = detector.proximity_candidate(query, graph, {near}, &new_partner);
    ASSERT_TRUE(c);
    EXPECT_EQ(graph.node(c->node).key, (KeyframeKey{"far", 2}));
    EXPECT_TRUE(new_partner);
    // The start of the verification is the query's pose in the candidate's frame.
    EXPECT_NEAR(c->initial.translation().y(), -4.0, 1e-12);

    std::vector<std::uint32_t> both{near, far};
    std::sort(both.begin(), both.end());
    c = detector.proximity_candidate(query, graph, both, &new_partner);
    ASSERT_TRUE(c);
    EXPECT_EQ(graph.node(c->node).key, (KeyframeKey{"near", 2}));
    EXPECT_FALSE(new_partner);
  }
}

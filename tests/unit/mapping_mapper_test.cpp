// The mapper on a synthetic street: duplicates and out-of-order keyframes, a drifting
// out-and-back drive corrected by its loops, and two vehicles starting at unknown relative
// poses merged into one frame.

#include "litamin2/core/voxelizer.hpp"
#include "litamin2/mapping/loop_detector.hpp"
#include "litamin2/mapping/mapper.hpp"
#include "support/street_drive.hpp"
#include "support/synthetic_scene.hpp"

#include <gtest/gtest.h>

#include <algorithm>

using namespace litamin2;
using namespace litamin2::mapping;
using litamin2::testing::drive;
using litamin2::testing::out_and_back;
using litamin2::testing::planar_pose;

namespace {

MapperConfig street_config() {
  MapperConfig config;
  config.place.min_travel_gap = 20.0;  // the street is 60 m long
  // Two vehicles' frames merge at two agreeing loops this far apart: the vehicles of
  // TwoVehicles find each other over the first 18 m of the street only.
  config.place.merge_min_separation = 10.0;
  return config;
}

/// Largest position error of the stream's corrected keyframes against the truth, both taken
/// relative to the first keyframe of `reference`.
double worst_error(const Mapper& mapper, const std::string& stream,
                   const std::vector<Eigen::Isometry3d>& truth, const Eigen::Isometry3d& origin) {
  double worst = 0.0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const auto pose = mapper.pose({stream, i});
    if (!pose) continue;
    worst = std::max(
        worst, (pose->pose.translation() - (origin.inverse() * truth[i]).translation()).norm());
  }
  return worst;
}

}  // namespace

TEST(MappingMapper, DuplicatesAreIgnoredAndLateKeyframesChainByOdometry) {
  const auto truth = out_and_back();
  auto keyframes =
      drive("a", std::vector<Eigen::Isometry3d>(truth.begin(), truth.begin() + 6), 0.0, 1);
  MapperConfig config = street_config();
  config.place.proximity_radius = 0.0;  // no loops: poses must equal the odometry
  config.place.max_descriptor_distance = 0.0;
  Mapper mapper(config);
  for (std::size_t i : {3u, 0u, 5u, 1u, 4u, 2u}) {
    EXPECT_EQ(mapper.add_keyframe(keyframes[i]), AddStatus::kAdded);
  }
  EXPECT_EQ(mapper.add_keyframe(keyframes[4]), AddStatus::kDuplicate);
  EXPECT_EQ(mapper.stats().keyframes, 6u);
  EXPECT_EQ(mapper.stats().duplicates, 1u);
  // The first keyframe to arrive (id 3) took its odometry pose and the others were chained to
  // it, so every pose is the odometry pose.
  for (const KeyframePose& p : mapper.poses()) {
    EXPECT_TRUE(p.pose.isApprox(keyframes[p.key.id].odom_pose, 1e-9)) << p.key.id;
    EXPECT_EQ(p.frame, "a");
  }
  const auto c = mapper.correction("a", 4);
  ASSERT_TRUE(c);
  EXPECT_EQ(c->key.id, 4u);
  EXPECT_TRUE(c->pose.isApprox(Eigen::Isometry3d::Identity(), 1e-9));
}

TEST(MappingMapper, LoopsCorrectADriftingDrive) {
  const auto truth = out_and_back();
  const auto keyframes = drive("a", truth, 0.05, 1);
  Mapper without(street_config());
  MapperConfig off = street_config();
  off.place.proximity_radius = 0.0;
  off.place.max_descriptor_distance = 0.0;
  Mapper odometry_only(off);
  for (const auto& kf : keyframes) {
    odometry_only.add_keyframe(kf);
    without.add_keyframe(kf);
    without.optimize();
  }
  // The local optimisations ran as loops came; the full pass (the aggregator's background
  // one) settles the whole drive.
  without.optimize_full();
  const double before = worst_error(odometry_only, "a", truth, truth[0]);
  const double after = worst_error(without, "a", truth, truth[0]);
  EXPECT_GT(without.stats().verified, 5u) << without.stats().candidates << " candidates";
  EXPECT_GT(before, 0.5);
  EXPECT_LT(after, 0.6 * before) << "before " << before << " m";
  // The global map is built from every keyframe at its corrected pose.
  EXPECT_GT(without.global_map().size(), 100u);
}

TEST(MappingMapper, LoopSpacingSpacesAStreamsLoopsAlongItsPath) {
  // place_recognition.loop_spacing: after a verified loop the stream searches again only this
  // far along its path, so its loops (by their newer keyframe) are at least that far apart.
  const auto keyframes = drive("a", out_and_back(), 0.05, 1);
  MapperConfig spaced_config = street_config();
  spaced_config.place.loop_spacing = 15.0;
  Mapper every(street_config()), spaced(spaced_config);
  for (const auto& kf : keyframes) {
    every.add_keyframe(kf);
    spaced.add_keyframe(kf);
  }
  every.optimize();
  spaced.optimize();
  ASSERT_GT(spaced.loops().size(), 1u);
  EXPECT_LT(spaced.loops().size(), every.loops().size());
  std::vector<double> paths;
  for (const LoopEdge& loop : spaced.loops()) {
    const KeyframeKey& newer = loop.from.id > loop.to.id ? loop.from : loop.to;
    paths.push_back(spaced.node(newer)->path_length);
  }
  std::sort(paths.begin(), paths.end());
  for (std::size_t i = 1; i < paths.size(); ++i)
    EXPECT_GE(paths[i] - paths[i - 1], spaced_config.place.loop_spacing - 1e-9) << i;
}

TEST(MappingMapper, VerificationBudgetBoundsTheCandidatesVerified) {
  // place_recognition.verification_budget_per_keyframe: the candidates verified by searches of
  // all keyframes stay within the allowance (budget per keyframe, at most 100 keyframes'
  // worth saved), the searches past it are counted, and the stream still finds loops.
  const auto keyframes = drive("a", out_and_back(), 0.05, 1);
  MapperConfig budget_config = street_config();
  budget_config.place.verification_budget_per_keyframe = 0.1;
  Mapper every(street_config()), budgeted(budget_config);
  for (const auto& kf : keyframes) {
    every.add_keyframe(kf);
    budgeted.add_keyframe(kf);
  }
  every.optimize();
  budgeted.optimize();
  const MapperStats s = budgeted.stats();
  // One stream, one group: every candidate comes from a search of all keyframes. A search
  // may verify two candidates, so the allowance can end at -1.
  const double allowance = 0.1 * static_cast<double>(keyframes.size()) + 1.0;
  EXPECT_LE(static_cast<double>(s.candidates), allowance);
  ASSERT_LT(s.candidates, every.stats().candidates);
  EXPECT_GT(s.searches_over_budget, 0u);
  EXPECT_EQ(every.stats().searches_over_budget, 0u);
  EXPECT_GT(budgeted.loops().size(), 0u);
}

/// Two vehicles on the street: b drives it later, starting at the far end, so its odometry
/// frame (its own first pose) is 60 m and 180 degrees from a's. Keyframes are given to the
/// mapper in `arrival` order, all of one vehicle and then all of the other.
class TwoVehicles : public ::testing::Test {
 protected:
  TwoVehicles() {
    const auto truth = out_and_back();
    truth_a.assign(truth.begin(), truth.begin() + 21);
    truth_b.assign(truth.begin() + 21, truth.end());
    a = drive("a", truth_a, 0.0, 1);
    b = drive("b", truth_b, 0.0, 2);
    for (auto& kf : b) kf.stamp.nanoseconds += 1000000000;
  }

  /// Checks that both vehicles end in a's frame, which is the map's, each keyframe within
  /// 0.3 m of the truth relative to a's first pose.
  void expect_both_in_a_frame(const Mapper& mapper) {
    ASSERT_FALSE(mapper.loops().empty());
    EXPECT_EQ(mapper.map_anchor(), "a");
    // Joined once, by two agreeing loops (merge_confirmation.hpp); the first waited.
    EXPECT_EQ(mapper.stats().merges, 1u);
    EXPECT_GE(mapper.stats().merges_pending, 1u);
    const auto pose_b = mapper.pose({"b", 10});
    ASSERT_TRUE(pose_b);
    EXPECT_EQ(pose_b->frame, "a") << "b's keyframes are not in a's frame";
    EXPECT_LT(worst_error(mapper, "b", truth_b, truth_a[0]), 0.3);
    EXPECT_LT(worst_error(mapper, "a", truth_a, truth_a[0]), 0.3);
  }

  std::vector<Eigen::Isometry3d> truth_a, truth_b;
  std::vector<Keyframe> a, b;
};

TEST_F(TwoVehicles, AtUnknownRelativePosesEndInOneFrame) {
  Mapper mapper(street_config());
  for (const auto& kf : a) mapper.add_keyframe(kf);
  for (const auto& kf : b) mapper.add_keyframe(kf);
  mapper.optimize();
  expect_both_in_a_frame(mapper);
}

TEST_F(TwoVehicles, MapFrameDoesNotDependOnArrivalOrder) {
  // b's keyframes reach the mapper first (b's daemon published first), but a's data comes
  // first in time: the map and the merged group are still in a's frame, as a mapper rebuilt
  // from the store in canonical order would have them.
  Mapper mapper(street_config());
  for (const auto& kf : b) mapper.add_keyframe(kf);
  EXPECT_EQ(mapper.map_anchor(), "b");  // alone, b is the map
  for (const auto& kf : a) mapper.add_keyframe(kf);
  mapper.optimize();
  expect_both_in_a_frame(mapper);
}

TEST_F(TwoVehicles, ASearchOfOtherGroupsFindsOnlyTheirKeyframes) {
  // Within loop_spacing after a loop in its own group a stream searches only other groups
  // (SearchScope::kOtherGroups): the descriptor's candidate is another group's keyframe, and
  // there is no proximity candidate (it is of the query's group).
  MapperConfig config = street_config();
  config.place.merge_confirmations = 100;  // the two groups stay apart
  Mapper mapper(config);
  for (const auto& kf : a) mapper.add_keyframe(kf);
  for (const auto& kf : b) mapper.add_keyframe(kf);
  const KeyframeGraph& graph = mapper.graph();
  const StreamGroups& groups = graph.groups();
  ASSERT_NE(groups.anchor_of("a"), groups.anchor_of("b"));
  const LoopDetector detector(mapper.config());
  std::size_t found = 0;
  for (std::uint64_t id = 0; id < b.size(); ++id) {
    const auto query = static_cast<std::uint32_t>(graph.find({"b", id}));
    if (const auto c = detector.descriptor_candidate(query, graph, SearchScope::kOtherGroups)) {
      EXPECT_EQ(graph.node(c->node).key.stream, "a") << id;
      ++found;
    }
    // a's own drive passes every place twice: searching a's keyframes among other groups
    // never returns one of a's.
    const auto qa = static_cast<std::uint32_t>(graph.find({"a", id}));
    if (const auto c = detector.descriptor_candidate(qa, graph, SearchScope::kOtherGroups)) {
      EXPECT_EQ(graph.node(c->node).key.stream, "b") << id;
    }
  }
  EXPECT_GT(found, b.size() / 2) << "b's places are a's: most searches should find one";
}

// The local optimisation after each loop against the full one: on the drifting street drive,
// the local optimisations alone end within a stated distance of the full pass's poses, and
// the full pass over rigid segments within a stated distance of the keyframe-level one.

#include "litamin2/mapping/mapper.hpp"
#include "support/keyframe_pose_difference.hpp"
#include "support/street_drive.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>

using namespace litamin2;
using namespace litamin2::mapping;
using litamin2::testing::drive;
using litamin2::testing::largest_translation_difference;
using litamin2::testing::out_and_back;

namespace {

double largest_difference(const Mapper& a, const Mapper& b) {
  return largest_translation_difference(a.poses(), b.poses());
}

}  // namespace

TEST(MappingLocalOptimization, EndsCloseToTheFullOptimisation) {
  const auto keyframes = drive("a", out_and_back(), 0.05, 1);
  MapperConfig config;
  config.place.min_travel_gap = 20.0;
  MapperConfig keyframe_level = config;
  keyframe_level.graph.segment_keyframes = 1;
  Mapper local(config), segments(config), full(keyframe_level);
  for (const auto& kf : keyframes) {
    for (Mapper* m : {&local, &segments, &full}) {
      m->add_keyframe(kf);
      m->optimize();
    }
  }
  segments.optimize_full();
  full.optimize_full();
  ASSERT_GT(full.loops().size(), 5u);
  ASSERT_EQ(local.loops().size(), full.loops().size());
  // Tolerance (the drive drifts by 1.0 m without loops): the local optimisations alone, and
  // the full pass over 10-keyframe segments, end within 0.15 m of the keyframe-level full
  // optimisation (measured with the default local_hold_loops 2: 0.085 and 0.079 m; 0.10 and
  // 0.09 m with every older end freed).
  const double local_gap = largest_difference(local, full);
  const double segment_gap = largest_difference(segments, full);
  EXPECT_LT(local_gap, 0.15);
  EXPECT_LT(segment_gap, 0.15);
  std::printf("local vs full %.3f m, segments vs full %.3f m\n", local_gap, segment_gap);
}

// pose_graph.local_hold_loops: a new loop's older end whose neighbourhood already holds that
// many checked loops stays constant (bit-identical) through the solve, the solves are smaller,
// and the local optimisations still end within the stated tolerance of the full one.
TEST(MappingLocalOptimization, HeldOlderEndsStayConstantAndEndCloseToTheFull) {
  const auto keyframes = drive("a", out_and_back(), 0.05, 1);
  MapperConfig config;
  config.place.min_travel_gap = 20.0;
  config.graph.local_hold_loops = 0;  // every older end freed (the default holds at 2)
  MapperConfig holding = config;
  holding.graph.local_hold_loops = 1;
  MapperConfig keyframe_level = config;
  keyframe_level.graph.segment_keyframes = 1;
  Mapper held(holding), freed(config), full(keyframe_level);
  int held_solves = 0;
  long held_keyframes = 0, freed_keyframes = 0;
  for (const auto& kf : keyframes) {
    std::vector<LoopEdge> new_loops;
    held.add_keyframe(kf, &new_loops);
    std::vector<Eigen::Isometry3d> older_before;
    for (const LoopEdge& loop : new_loops) older_before.push_back(held.node(loop.from)->pose);
    const OptimizeSummary s = held.optimize();
    held_keyframes += s.keyframes;
    // One keyframe at a time: at most one new loop, so a held end is that loop's older end.
    ASSERT_LE(new_loops.size(), 1u);
    if (s.held_ends > 0) {
      ++held_solves;
      ASSERT_EQ(new_loops.size(), 1u);
      EXPECT_TRUE(held.node(new_loops[0].from)->pose.isApprox(older_before[0], 0.0))
          << "the held older end moved";
    }
    freed.add_keyframe(kf);
    freed_keyframes += freed.optimize().keyframes;
    full.add_keyframe(kf);
    full.optimize();
  }
  full.optimize_full();
  ASSERT_GT(held_solves, 0);
  ASSERT_EQ(held.loops().size(), full.loops().size());
  EXPECT_LT(held_keyframes, freed_keyframes);
  // Tolerance (the drive drifts by 1.0 m without loops): the local optimisations alone end
  // within 0.25 m of the keyframe-level full optimisation (measured: 0.19 m, against 0.10 with
  // every end freed: a held end takes none of the correction), and so does the result of the
  // full pass over 10-keyframe segments after them (measured: 0.18 m; the shape within a
  // segment is the local optimisations').
  const double local_gap = largest_difference(held, full);
  EXPECT_LT(local_gap, 0.25);
  held.optimize_full();
  const double full_pass_gap = largest_difference(held, full);
  EXPECT_LT(full_pass_gap, 0.25);
  std::printf(
      "held vs full %.3f m, after its full pass %.3f m; %d of the solves held their "
      "older end; %ld keyframes in all solves (%ld with every end freed)\n",
      local_gap, full_pass_gap, held_solves, held_keyframes, freed_keyframes);
}

// pose_graph.local_max_free_keyframes: a bounded local solve frees at most that many
// keyframes (every keyframe beyond the bound keeps its pose bit for bit) and always its new
// loop's newer end; the bounded local optimisations, and the full pass after them, end within
// a stated tolerance of the full optimisation.
TEST(MappingLocalOptimization, BoundedSolvesHoldTheRestFixedAndEndCloseToTheFull) {
  const auto keyframes = drive("a", out_and_back(), 0.05, 1);
  MapperConfig config;
  config.place.min_travel_gap = 20.0;
  config.graph.local_max_free_keyframes = 0;  // no bound
  MapperConfig bounding = config;
  constexpr int kBound = 8;
  bounding.graph.local_max_free_keyframes = kBound;
  MapperConfig keyframe_level = config;
  keyframe_level.graph.segment_keyframes = 1;
  Mapper bounded(bounding), unbounded(config), full(keyframe_level);
  int bounded_solves = 0, widened_solves = 0, largest_unbounded = 0;
  for (const auto& kf : keyframes) {
    std::vector<LoopEdge> new_loops;
    bounded.add_keyframe(kf, &new_loops);
    const auto before = bounded.poses();
    const Eigen::Isometry3d newer_before =
        new_loops.empty() ? Eigen::Isometry3d::Identity() : bounded.node(new_loops[0].to)->pose;
    const OptimizeSummary s = bounded.optimize();
    const auto after = bounded.poses();
    ASSERT_EQ(before.size(), after.size());
    int moved = 0;
    for (std::size_t i = 0; i < after.size(); ++i)
      if (!after[i].pose.isApprox(before[i].pose, 0.0)) ++moved;
    EXPECT_LE(moved, s.free_keyframes) << "a keyframe beyond the bound moved";
    if (s.widened) ++widened_solves;
    // At most the bound, or the new loop's span along the stream when its older end is free
    // (the keyframes between two ends are kept); a widened solve (the bounded region failed
    // to fit the new loop) is the whole region.
    if (!s.widened && !new_loops.empty()) {
      const auto span = static_cast<int>(std::llabs(static_cast<long long>(new_loops[0].to.id) -
                                                    static_cast<long long>(new_loops[0].from.id)) +
                                         1);
      EXPECT_LE(s.free_keyframes, s.held_ends > 0 ? kBound : std::max(kBound, span));
    }
    if (s.bounded_keyframes > 0) {
      ++bounded_solves;
      ASSERT_EQ(new_loops.size(), 1u);
      EXPECT_FALSE(bounded.node(new_loops[0].to)->pose.isApprox(newer_before, 0.0))
          << "the new loop's newer end was held";
    }
    unbounded.add_keyframe(kf);
    largest_unbounded = std::max(largest_unbounded, unbounded.optimize().free_keyframes);
    full.add_keyframe(kf);
    full.optimize();
  }
  full.optimize_full();
  ASSERT_GT(bounded_solves, 10);
  EXPECT_GT(largest_unbounded, kBound);
  ASSERT_EQ(unbounded.loops().size(), full.loops().size());
  const double local_gap = largest_difference(bounded, full);
  const double unbounded_gap = largest_difference(unbounded, full);
  bounded.optimize_full();
  const double full_pass_gap = largest_difference(bounded, full);
  // Tolerances (the drive drifts by 1.0 m without loops; every keyframe of the way back
  // closes a loop, so each solve's region is ~11 keyframes and the bound of 8 holds a quarter
  // of it fixed): the bounded local optimisations end within 0.25 m of the keyframe-level full
  // optimisation, and so does the full pass after them (measured 0.18 and 0.17 m, against
  // 0.085 m unbounded); their poses differ, and so do the loops found and kept after them: at
  // least 80 % of the full's (measured 30 of 34, four dropped as inconsistent even by the
  // whole region).
  EXPECT_LT(local_gap, 0.25);
  EXPECT_LT(full_pass_gap, 0.25);
  EXPECT_GE(bounded.loops().size() * 5, full.loops().size() * 4);
  std::printf(
      "bounded vs full %.3f m (unbounded %.3f m), after its full pass %.3f m; %d bounded "
      "solves, %d widened; loops %zu (full %zu); largest unbounded solve %d free keyframes\n",
      local_gap, unbounded_gap, full_pass_gap, bounded_solves, widened_solves,
      bounded.loops().size(), full.loops().size(), largest_unbounded);
}

// The map frame is the first stream's first pose: a local solve whose region reaches that
// keyframe while other keyframes hold the region (here: a loop back to the start, its newer
// end's stretch bounded by local_max_keyframes, its older end freed) keeps it bit for bit, and
// so does the full pass; the rest still ends close to the full optimisation.
TEST(MappingLocalOptimization, TheFirstKeyframeHoldsTheMapFrame) {
  const auto keyframes = drive("a", out_and_back(), 0.05, 1);
  MapperConfig config;
  config.place.min_travel_gap = 20.0;
  config.graph.local_hold_loops = 0;     // the older end, near the start, is freed
  config.graph.local_max_keyframes = 5;  // the newer end's stretch is held beyond 5
  MapperConfig keyframe_level = config;
  keyframe_level.graph.segment_keyframes = 1;
  Mapper local(config), full(keyframe_level);
  const KeyframeKey first{"a", 0};
  int solves_near_start = 0;
  for (const auto& kf : keyframes) {
    std::vector<LoopEdge> new_loops;
    local.add_keyframe(kf, &new_loops);
    const OptimizeSummary s = local.optimize();
    for (const LoopEdge& loop : new_loops)
      if (loop.from.id <= 3 && s.keyframes > s.free_keyframes + 1) ++solves_near_start;
    ASSERT_TRUE(local.node(first)->pose.isApprox(keyframes[0].odom_pose, 0.0))
        << "the map frame's keyframe moved in a local solve at keyframe " << kf.key.id;
    full.add_keyframe(kf);
    full.optimize();
  }
  ASSERT_GT(solves_near_start, 0) << "no solve reached the start while other keyframes held";
  local.optimize_full();
  full.optimize_full();
  EXPECT_TRUE(local.node(first)->pose.isApprox(keyframes[0].odom_pose, 0.0));
  EXPECT_TRUE(full.node(first)->pose.isApprox(keyframes[0].odom_pose, 0.0));
  // Tolerance as in EndsCloseToTheFullOptimisation (the drive drifts by 1.0 m without loops).
  const double gap = largest_difference(local, full);
  EXPECT_LT(gap, 0.15);
  std::printf("local vs full %.3f m; %d solves near the start\n", gap, solves_near_start);
}

// The full pass applied again and again (the aggregator runs one every few seconds for as long
// as it lives): the keyframes' rotations stay rotations. A correction made from a pose whose
// rotation is off orthonormal by e (R^T R = I + 2F) and applied to that pose doubles e, so
// without a projection back onto SO(3) ~45 passes turn rounding (1e-16) into 1e-3 (the store
// then refuses the pose) and ~230 into the runaway solutions seen at 10^5 keyframes.

#include "litamin2/mapping/mapper.hpp"
#include "support/keyframe_pose_difference.hpp"
#include "support/street_drive.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <memory>

using namespace litamin2;
using namespace litamin2::mapping;
using litamin2::testing::drive;
using litamin2::testing::largest_translation_difference;
using litamin2::testing::out_and_back;

namespace {

double worst_orthonormality(const Mapper& mapper) {
  double worst = 0.0;
  for (const KeyframeNode& n : mapper.graph().nodes()) {
    const Eigen::Matrix3d r = n.pose.linear();
    worst =
        std::max(worst, (r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff());
  }
  return worst;
}

}  // namespace

TEST(MappingFullPass, RepeatedPassesKeepRotationsOrthonormalAndPosesStill) {
  const auto keyframes = drive("a", out_and_back(), 0.05, 1);
  MapperConfig config;
  config.place.min_travel_gap = 20.0;
  config.graph.full_pass_min_shift = 0.0;  // every pass rewrites every pose
  config.graph.full_pass_min_turn_deg = 0.0;
  // Fixed cuts: each pass solves the same problem (shifted ones converge over passes).
  config.graph.full_pass_shift_segments = false;
  Mapper mapper(config);
  for (const auto& kf : keyframes) {
    mapper.add_keyframe(kf);
    mapper.optimize();
  }
  mapper.optimize_full();
  ASSERT_GT(mapper.loops().size(), 5u);
  const std::vector<KeyframePose> settled = mapper.poses();
  // 200 passes over an unchanged graph: each solves to (nearly) the same poses.
  for (int pass = 0; pass < 200; ++pass) {
    FullPassProblem problem = mapper.full_pass_problem();
    GraphOptimizer::solve_full_pass(problem);
    ASSERT_TRUE(problem.result.usable)
        << "pass " << pass << ", rotations off orthonormal by " << worst_orthonormality(mapper);
    mapper.apply_full_pass(problem);
  }
  EXPECT_LT(worst_orthonormality(mapper), 1e-12);
  const std::vector<KeyframePose> after = mapper.poses();
  ASSERT_EQ(after.size(), settled.size());
  const double moved = largest_translation_difference(after, settled);
  // Tolerance: the solver stops at its function tolerance, so a pass may move a converged
  // graph by micrometres; 200 of them stay below a millimetre.
  EXPECT_LT(moved, 1e-3);
  EXPECT_EQ(mapper.stats().diverged, 0u);
}

TEST(MappingFullPass, SegmentsGrowInMultiplesToKeepThePassBounded) {
  // pose_graph.full_pass_max_segments: up to segment_keyframes x that many keyframes the
  // segments are segment_keyframes long; beyond, the smallest multiple that keeps their number
  // within the bound.
  PoseGraphConfig config;
  config.segment_keyframes = 10;
  config.full_pass_max_segments = 20000;
  EXPECT_EQ(full_pass_segment_keyframes(config, 0), 10u);
  EXPECT_EQ(full_pass_segment_keyframes(config, 200000), 10u);
  EXPECT_EQ(full_pass_segment_keyframes(config, 200001), 20u);
  EXPECT_EQ(full_pass_segment_keyframes(config, 1000000), 50u);
  config.full_pass_max_segments = 0;  // no bound
  EXPECT_EQ(full_pass_segment_keyframes(config, 1000000), 10u);
}

TEST(MappingFullPass, ABoundedPassSolvesFewerSegmentsAndStillCorrects) {
  // The same drive with a pass of at most 4 segments: the segments hold more keyframes, the
  // pass has that many nodes (one stream: at most one partial segment more), and it is solved
  // and applied like the unbounded one, leaving the poses close to it.
  const auto keyframes = drive("a", out_and_back(), 0.05, 1);
  MapperConfig config;
  config.place.min_travel_gap = 20.0;
  MapperConfig bounded_config = config;
  bounded_config.graph.full_pass_max_segments = 4;
  Mapper full(config), bounded(bounded_config);
  for (const auto& kf : keyframes) {
    full.add_keyframe(kf);
    full.optimize();
    bounded.add_keyframe(kf);
    bounded.optimize();
  }
  ASSERT_GT(full.loops().size(), 5u);
  const FullPassProblem unbounded_problem = full.full_pass_problem();
  FullPassProblem problem = bounded.full_pass_problem();
  EXPECT_EQ(unbounded_problem.segment_keyframes, 10u);
  EXPECT_GT(problem.segment_keyframes, 10u);
  EXPECT_EQ(problem.segment_keyframes % 10, 0u);
  EXPECT_LE(problem.poses.size(), 5u);
  EXPECT_LT(problem.poses.size(), unbounded_problem.poses.size());
  GraphOptimizer::solve_full_pass(problem);
  ASSERT_TRUE(problem.result.usable);
  bounded.apply_full_pass(problem);
  full.optimize_full();
  const std::vector<KeyframePose> a = full.poses(), b = bounded.poses();
  ASSERT_EQ(a.size(), b.size());
  const double worst = largest_translation_difference(a, b);
  // Tolerance: rigid stretches of ~a quarter of the drive cannot bend as ten-keyframe ones
  // can; the local optimisations have already placed both, so they stay within decimetres.
  EXPECT_LT(worst, 0.5);
}

TEST(MappingFullPass, APassLeavesTheKeyframesItWouldMoveLessThanTheThreshold) {
  // pose_graph.full_pass_min_shift: the same solved pass applied to two identical mappers,
  // one moving every keyframe, one with the threshold at the median shift: below it a
  // keyframe keeps its pose bit for bit, above it the pose is the other mapper's.
  const auto keyframes = drive("a", out_and_back(), 0.05, 1);
  MapperConfig config;
  config.place.min_travel_gap = 20.0;
  config.graph.full_pass_min_shift = 0.0;
  config.graph.full_pass_min_turn_deg = 0.0;
  auto build = [&](const MapperConfig& c) {
    Mapper m(c);
    for (const auto& kf : keyframes) {
      m.add_keyframe(kf);
      m.optimize();
    }
    return m;
  };
  Mapper every = build(config);
  ASSERT_GT(every.loops().size(), 5u);
  FullPassProblem problem = every.full_pass_problem();
  GraphOptimizer::solve_full_pass(problem);
  ASSERT_TRUE(problem.result.usable);
  const std::vector<KeyframePose> before = every.poses();
  every.apply_full_pass(problem);
  const std::vector<KeyframePose> after = every.poses();
  ASSERT_EQ(after.size(), before.size());
  std::vector<double> shift(before.size());
  for (std::size_t i = 0; i < before.size(); ++i)
    shift[i] = (after[i].pose.translation() - before[i].pose.translation()).norm();
  std::vector<double> sorted = shift;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double median = sorted[sorted.size() / 2];
  ASSERT_GT(median, 1e-6);

  MapperConfig threshold_config = config;
  threshold_config.graph.full_pass_min_shift = median;
  threshold_config.graph.full_pass_min_turn_deg = 10.0;  // the shift decides
  Mapper thresholded = build(threshold_config);
  ASSERT_EQ(thresholded.poses().size(), before.size());
  thresholded.apply_full_pass(problem);
  const std::vector<KeyframePose> kept = thresholded.poses();
  std::size_t moved = 0, left = 0;
  for (std::size_t i = 0; i < before.size(); ++i) {
    ASSERT_EQ(kept[i].key, before[i].key);
    if (shift[i] < median) {
      EXPECT_TRUE(kept[i].pose.matrix() == before[i].pose.matrix()) << i;
      ++left;
    } else {
      EXPECT_TRUE(kept[i].pose.matrix() == after[i].pose.matrix()) << i;
      ++moved;
    }
  }
  EXPECT_GT(left, 0u);
  EXPECT_GT(moved, 0u);
  EXPECT_EQ(thresholded.stats().full_pass_keyframes_moved, moved);
  EXPECT_EQ(every.stats().full_pass_keyframes_moved, before.size());
}

TEST(MappingFullPass, EachPassCutsTheSegmentsOneKeyframeFurther) {
  // pose_graph.full_pass_shift_segments: a stream's first segment starts at its first keyframe
  // (and holds the frame), the others every segment_keyframes from the pass's shift on.
  const auto keyframes = drive("a", out_and_back(), 0.05, 1);
  for (bool shift : {true, false}) {
    MapperConfig config;
    config.graph.segment_keyframes = 10;
    config.graph.full_pass_shift_segments = shift;
    Mapper mapper(config);
    for (const auto& kf : keyframes) mapper.add_keyframe(kf);
    ASSERT_GT(keyframes.size(), 30u);
    for (std::size_t pass = 0; pass < 12; ++pass) {
      const FullPassProblem problem = mapper.full_pass_problem();
      const std::size_t s = shift ? pass % 10 : 0;
      for (std::size_t k = 0; k < keyframes.size(); ++k) {
        // Cuts at 0 and at k = s, s + 10, ... (k > 0).
        const std::size_t expected = (k + 10 - s) / 10 - (s == 0 ? 1 : 0);
        EXPECT_EQ(problem.segment_of_node[k], static_cast<std::int32_t>(expected))
            << "shift " << shift << " pass " << pass << " keyframe " << k;
      }
      EXPECT_TRUE(problem.fixed[0]);
    }
  }
}

TEST(MappingFullPass, ShiftedCutsApproachTheKeyframeLevelSolution) {
  // With fixed cuts the shape within each segment is the local optimisations' for good; with
  // shifted cuts repeated passes move towards the solution of the whole keyframe graph.
  const auto keyframes = drive("a", out_and_back(), 0.05, 1);
  auto mapped = [&](int segment, bool shift, int passes) {
    MapperConfig config;
    config.place.min_travel_gap = 20.0;
    config.graph.segment_keyframes = segment;
    config.graph.full_pass_shift_segments = shift;
    config.graph.full_pass_min_shift = 0.0;
    config.graph.full_pass_min_turn_deg = 0.0;
    auto mapper = std::make_unique<Mapper>(config);
    for (const auto& kf : keyframes) {
      mapper->add_keyframe(kf);
      mapper->optimize();
    }
    for (int pass = 0; pass < passes; ++pass) mapper->optimize_full();
    return mapper;
  };
  const auto exact = mapped(1, false, 3);
  const auto fixed = mapped(10, false, 30);
  const auto shifted = mapped(10, true, 30);
  ASSERT_GT(exact->loops().size(), 5u);
  const double off_fixed = largest_translation_difference(fixed->poses(), exact->poses());
  const double off_shifted = largest_translation_difference(shifted->poses(), exact->poses());
  std::printf(
      "largest distance from the keyframe-level solution: fixed cuts %.4f m, shifted %.4f m\n",
      off_fixed, off_shifted);
  EXPECT_LT(off_shifted, 0.5 * off_fixed);
}

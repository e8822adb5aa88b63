// The coarse search of loop verification stops scoring a pose once it can no longer beat the
// best so far (nor the initial pose): over many starts around true and wrong places it picks
// the same pose, with the same fraction, as scoring all 243 poses to the end, and scores far
// fewer to the end. The bounded inlier count is exact whenever it reaches the number asked for.

#include "litamin2/core/correspondence_search.hpp"
#include "litamin2/core/voxelizer.hpp"
#include "litamin2/mapping/distribution_moments.hpp"
#include "litamin2/mapping/fitness_scorer.hpp"
#include "support/scene_views.hpp"
#include "support/synthetic_scene.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>

using namespace litamin2;
using namespace litamin2::mapping;
using litamin2::testing::planar_pose;

using litamin2::testing::map_of;
using litamin2::testing::mirrored;
using litamin2::testing::view;

TEST(MappingCoarseAlignment, BoundedPicksThePoseOfTheExhaustiveSearch) {
  const PointCloud scene = litamin2::testing::synthetic_scene(1);
  const PointCloud scene2 = litamin2::testing::synthetic_scene(2);
  const VoxelMap submap = map_of(view(scene, planar_pose(0, 0, 0)));
  const auto search = make_correspondence_search(CorrespondenceMethod::kKdTree, submap);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> offset(-6.0, 6.0), yaw(-40.0, 40.0);
  int bounded_scores = 0, exhaustive_scores = 0, cases = 0;
  for (int place = 0; place < 2; ++place) {
    const PointCloud& seen = place == 0 ? scene2 : mirrored(scene2);
    for (int i = 0; i < 12; ++i) {
      const Eigen::Isometry3d query = planar_pose(offset(rng), offset(rng), yaw(rng));
      const std::vector<Distribution> distributions = view(seen, query);
      const FitnessScorer scorer(distributions, submap, *search);
      ASSERT_GE(scorer.structure(), 20u);
      // Starts off the truth by up to a few metres and degrees.
      const Eigen::Isometry3d initial =
          query * planar_pose(offset(rng) / 3.0, offset(rng) / 3.0, yaw(rng) / 10.0);
      const CoarseAlignment all = coarse_alignment(scorer, 3.0, initial, M_PI / 60.0, false);
      const CoarseAlignment bounded = coarse_alignment(scorer, 3.0, initial, M_PI / 60.0, true);
      EXPECT_TRUE(bounded.pose.matrix() == all.pose.matrix()) << place << " " << i;
      EXPECT_EQ(bounded.fraction, all.fraction) << place << " " << i;
      EXPECT_EQ(all.full_scores, 243);
      bounded_scores += bounded.full_scores;
      exhaustive_scores += all.full_scores;
      ++cases;
      // The bounded count is exact when it reaches the number asked for, below it otherwise.
      const std::size_t stride = std::max<std::size_t>(1, scorer.structure() / 300);
      const Fitness f = scorer.score(initial, 0.75, stride);
      const auto exact = static_cast<std::size_t>(std::lround(f.fraction * scorer.tried(stride)));
      EXPECT_EQ(scorer.inliers(initial, 0.75, stride, 0), exact);
      EXPECT_EQ(scorer.inliers(initial, 0.75, stride, exact), exact);
      if (exact < scorer.tried(stride)) {
        EXPECT_LT(scorer.inliers(initial, 0.75, stride, exact + 1), exact + 1);
      }
    }
  }
  EXPECT_LT(bounded_scores, exhaustive_scores / 2)
      << "the bound let " << bounded_scores << " of " << exhaustive_scores << " through";
  std::cout << cases << " starts: " << bounded_scores << " of " << exhaustive_scores
            << " poses scored to the end\n";
}

// NearestCache: reusing searches across Newton iterations changes no answer (so no cost, no
// pose), and it does reuse.

#include "litamin2/core/correspondence_search.hpp"
#include "litamin2/core/nearest_cache.hpp"
#include "litamin2/core/registration.hpp"
#include "litamin2/core/so3.hpp"
#include "litamin2/core/voxel_map.hpp"
#include "litamin2/core/voxelizer.hpp"
#include "support/synthetic_scene.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <random>

namespace litamin2 {
namespace {

Eigen::Isometry3d small_motion(std::mt19937& rng, double translation, double rotation) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = so3_exp(rotation * Eigen::Vector3d(n(rng), n(rng), n(rng)));
  pose.translation() = translation * Eigen::Vector3d(n(rng), n(rng), n(rng));
  return pose;
}

class NearestCacheTest : public ::testing::Test {
 protected:
  void SetUp() override {
    map_.insert(testing::synthetic_scene(1), Eigen::Isometry3d::Identity());
    search_ = make_correspondence_search(CorrespondenceMethod::kKdTree, map_);
    Voxelizer voxelizer(voxels_);
    source_ = voxelizer.voxelize(testing::synthetic_scene(2));
  }
  VoxelizerConfig voxels_;
  VoxelMap map_{voxels_, VoxelMapConfig{}};
  std::unique_ptr<CorrespondenceSearch> search_;
  std::vector<Distribution> source_;
};

TEST_F(NearestCacheTest, AnswersAsTheSearchDoesForMovingQueries) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-30.0, 30.0);
  std::normal_distribution<double> step(0.0, 1.0);
  const auto& targets = map_.distributions();
  ASSERT_GT(targets.size(), 50u);
  const int slots = 200;
  NearestCache cache(*search_, targets, slots);
  std::vector<Eigen::Vector3d> queries(slots);
  for (auto& q : queries) q = Eigen::Vector3d(u(rng), u(rng), 0.1 * u(rng));
  const double max_distance_sq = 9.0;
  int found = 0;
  // Steps from centimetres (Newton's later iterations) to metres (a new query each time).
  for (const double scale : {0.005, 0.02, 0.1, 0.5, 2.0, 0.01}) {
    for (int round = 0; round < 5; ++round) {
      for (int i = 0; i < slots; ++i) {
        queries[i] += scale * Eigen::Vector3d(step(rng), step(rng), step(rng));
        const int expected = search_->nearest(queries[i], max_distance_sq);
        ASSERT_EQ(cache.nearest(i, queries[i], max_distance_sq), expected)
            << "slot " << i << " step " << scale;
        if (expected >= 0) ++found;
      }
    }
  }
  EXPECT_GT(found, slots);  // most queries have a match, so the comparison means something
  EXPECT_GT(cache.reused(), cache.searched());  // small steps are answered without a search
  EXPECT_GT(cache.searched(), static_cast<std::size_t>(slots));  // large ones search again
}

TEST_F(NearestCacheTest, CostAlongNewtonLikeStepsIsBitIdentical) {
  std::mt19937 rng(9);
  for (const CostMode mode : {CostMode::kIcp, CostMode::kIcpCov}) {
    RegistrationConfig config;
    config.mode = mode;
    NearestCache cache(*search_, map_.distributions(), source_.size());
    Eigen::Isometry3d pose = small_motion(rng, 0.5, 0.02);
    for (int iteration = 0; iteration < 8; ++iteration) {
      const CostEvaluation fresh = evaluate_cost(source_, map_, *search_, pose, config);
      const CostEvaluation cached = evaluate_cost(source_, map_, *search_, pose, config, &cache);
      EXPECT_EQ(cached.correspondences, fresh.correspondences);
      EXPECT_EQ(cached.cost, fresh.cost);
      EXPECT_EQ(0, std::memcmp(cached.gradient.data(), fresh.gradient.data(), sizeof(double) * 6));
      EXPECT_EQ(0, std::memcmp(cached.hessian.data(), fresh.hessian.data(), sizeof(double) * 36));
      pose = small_motion(rng, 0.02, 0.001) * pose;
    }
    EXPECT_GT(cache.reused(), 0u);
  }
}

}  // namespace
}  // namespace litamin2

// The global x/y/yaw search apart from the tracker: which scan distributions it scores, that
// the score peaks at the true pose of a scan taken 10 m and 25 deg away from the last pose,
// and the validation of its config.

#include "litamin2/core/config_error.hpp"
#include "litamin2/core/global_pose_search.hpp"
#include "litamin2/core/so3.hpp"
#include "litamin2/core/voxelizer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace litamin2 {
namespace {

/// Points on a flat ground 1.7 m below the sensor's origin height and on vertical wall segments
/// of random place, direction and length within 40 m (no symmetry a search could be fooled by).
PointCloud scene() {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  PointCloud cloud;
  for (double x = -40.0; x <= 40.0; x += 0.5)
    for (double y = -40.0; y <= 40.0; y += 0.5)
      cloud.points.emplace_back(static_cast<float>(x), static_cast<float>(y), -1.7f);
  for (int w = 0; w < 40; ++w) {
    const Eigen::Vector2d start(-35.0 + 70.0 * u(rng), -35.0 + 70.0 * u(rng));
    const double angle = 2.0 * M_PI * u(rng), length = 4.0 + 10.0 * u(rng);
    const Eigen::Vector2d dir(std::cos(angle), std::sin(angle));
    for (double s = 0.0; s < length; s += 0.2) {
      for (double z = -1.7; z < 3.0; z += 0.2) {
        const Eigen::Vector2d p = start + s * dir;
        cloud.points.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()),
                                  static_cast<float>(z));
      }
    }
  }
  return cloud;
}

PointCloud in_sensor_frame(const PointCloud& world, const Eigen::Isometry3d& sensor) {
  const Eigen::Isometry3f to_sensor = sensor.inverse().cast<float>();
  PointCloud scan;
  for (const Eigen::Vector3f& p : world.points) {
    const Eigen::Vector3f q = to_sensor * p;
    if (q.norm() < 30.0f) scan.points.push_back(q);
  }
  return scan;
}

TEST(GlobalPoseSearch, ScoresOnlyDistributionsThatConstrainXYOrYaw) {
  Distribution ground;  // a horizontal plane
  ground.cov = Eigen::Vector3d(1.0, 1.0, 1e-4).asDiagonal();
  ground.mean = Eigen::Vector3d(1.0, 0.0, -1.7);
  Distribution wall;  // a vertical plane
  wall.cov = Eigen::Vector3d(1e-4, 1.0, 1.0).asDiagonal();
  wall.mean = Eigen::Vector3d(5.0, 0.0, 0.0);
  Distribution round;
  round.mean = Eigen::Vector3d(0.0, 3.0, 0.0);
  const std::vector<Eigen::Vector3d> kept =
      search_points({ground, wall, round}, Eigen::Matrix3d::Identity(), 100);
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[0], wall.mean);
  EXPECT_EQ(kept[1], round.mean);
  // A sensor rolled by 90 deg sees the same ground plane as a wall of its own frame.
  const Eigen::Matrix3d rolled = so3_exp(Eigen::Vector3d(M_PI / 2.0, 0.0, 0.0));
  EXPECT_EQ(search_points({ground}, rolled, 100).size(), 1u);
  // Subsampled to at most max_sources.
  EXPECT_EQ(
      search_points(std::vector<Distribution>(100, wall), Eigen::Matrix3d::Identity(), 16).size(),
      16u);
}

TEST(GlobalPoseSearch, FindsAPoseTenMetresAndTwentyFiveDegreesAway) {
  const PointCloud world = scene();
  VoxelizerConfig voxels;
  VoxelMap map(voxels, VoxelMapConfig{});
  map.insert(world, Eigen::Isometry3d::Identity());  // the map: the scene in the world frame
  Eigen::Isometry3d truth = Eigen::Isometry3d::Identity();
  truth.linear() = so3_exp(Eigen::Vector3d(0.0, 0.0, 25.0 * M_PI / 180.0));
  truth.translation() = Eigen::Vector3d(9.0, -4.5, 0.0);
  const Eigen::Isometry3d last = Eigen::Isometry3d::Identity();
  const Eigen::Isometry3d predicted = last;  // the prediction knows nothing of the break
  Voxelizer voxelizer(voxels);
  const std::vector<Distribution> source =
      voxelizer.voxelize(in_sensor_frame(world, truth), predicted);
  GlobalPoseSearchConfig config;
  const std::vector<Eigen::Vector3d> points = search_points(source, predicted.linear(), 256);
  ASSERT_GT(points.size(), 30u);
  const std::vector<PoseCandidate> found = search_global_pose(points, map, last, predicted, config);
  ASSERT_FALSE(found.empty());
  ASSERT_LE(found.size(), static_cast<std::size_t>(config.candidates));
  for (std::size_t i = 1; i < found.size(); ++i) EXPECT_LE(found[i].score, found[i - 1].score);
  const Eigen::Isometry3d error = truth.inverse() * found.front().pose;
  // Within the finest grid's steps (2 m / 4, 5 deg / 4), not yet registered.
  EXPECT_LT(error.translation().norm(), 0.75);
  EXPECT_LT(Eigen::AngleAxisd(error.linear()).angle() * 180.0 / M_PI, 2.0);
  // The score is a mean agreement in [0, 1], higher at the truth than at the last pose.
  const PoseScorer scorer(map, 0.5);
  EXPECT_GT(scorer.score(points, truth), 0.3);
  EXPECT_LE(scorer.score(points, truth), 1.0);
  EXPECT_LT(scorer.score(points, last), 0.5 * scorer.score(points, truth));
}

TEST(GlobalPoseSearch, NothingToFindInAnEmptyMap) {
  const VoxelMap map(VoxelizerConfig{}, VoxelMapConfig{});
  EXPECT_TRUE(search_global_pose({Eigen::Vector3d(5.0, 0.0, 0.0)}, map,
                                 Eigen::Isometry3d::Identity(), Eigen::Isometry3d::Identity(),
                                 GlobalPoseSearchConfig{})
                  .empty());
}

TEST(GlobalPoseSearch, InvalidConfigIsRejected) {
  EXPECT_NO_THROW(validate(GlobalPoseSearchConfig{}));
  auto rejects = [](auto change) {
    GlobalPoseSearchConfig c;
    change(c);
    EXPECT_THROW(validate(c), ConfigError);
  };
  rejects([](GlobalPoseSearchConfig& c) { c.trigger_ratio = 1.0; });
  rejects([](GlobalPoseSearchConfig& c) { c.trigger_ratio = -0.1; });
  rejects([](GlobalPoseSearchConfig& c) { c.range_xy = 0.0; });
  rejects([](GlobalPoseSearchConfig& c) { c.range_xy = NAN; });
  rejects([](GlobalPoseSearchConfig& c) { c.coarse_step_xy = 0.05; });
  rejects([](GlobalPoseSearchConfig& c) { c.coarse_step_xy = 20.0; });  // above range_xy
  rejects([](GlobalPoseSearchConfig& c) {  // a coarse grid of 161^2 x 91 poses
    c.range_xy = 80.0;
    c.coarse_step_xy = 1.0;
    c.coarse_step_yaw_deg = 1.0;
  });
  rejects([](GlobalPoseSearchConfig& c) { c.levels = 0; });
  rejects([](GlobalPoseSearchConfig& c) { c.candidates = 0; });
  rejects([](GlobalPoseSearchConfig& c) { c.max_sources = 8; });
  rejects([](GlobalPoseSearchConfig& c) { c.accept_ratio = 0.0; });
}

}  // namespace
}  // namespace litamin2

// Voxel moments, the voxeliser and the map: exact moment transforms, moments far from the
// origin, and the keyframe merge path against re-voting the points.

#include "litamin2/core/so3.hpp"
#include "litamin2/core/voxel_map.hpp"
#include "litamin2/core/voxel_moments.hpp"
#include "litamin2/core/voxelizer.hpp"
#include "support/synthetic_scene.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace litamin2 {
namespace {

TEST(VoxelMoments, TransformedEqualsMomentsOfTransformedPoints) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  VoxelMoments original;
  original.origin = Eigen::Vector3d(31.5, -7.5, 1.5);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 50; ++i) {
    points.push_back(original.origin + Eigen::Vector3d(u(rng), u(rng), 0.2 * u(rng)));
    original.add(points.back());
  }
  const Eigen::Matrix3d r = so3_exp(Eigen::Vector3d(0.01, -0.02, 0.3));
  const Eigen::Vector3d t(0.4, -0.1, 0.05);
  const Eigen::Vector3d new_origin(28.5, 4.5, 1.5);
  VoxelMoments direct;
  direct.origin = new_origin;
  for (const auto& p : points) direct.add(r * p + t);
  const VoxelMoments moved = original.transformed(r, t, new_origin);
  EXPECT_EQ(moved.count, direct.count);
  EXPECT_LT((moved.sum - direct.sum).norm(), 1e-9);
  EXPECT_LT((moved.sum_sq - direct.sum_sq).norm(), 1e-9);
}

TEST(VoxelMoments, CovarianceSurvivesFarFromTheOrigin) {
  // A flat patch 80 km away: float sums of x^2 would lose the 1 cm thickness entirely.
  VoxelMoments m;
  m.origin = Eigen::Vector3d(80000.5, 80000.5, 0.5);
  std::mt19937 rng(1);
  std::normal_distribution<double> thin(0.0, 0.01);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 2000; ++i) m.add(m.origin + Eigen::Vector3d(u(rng), u(rng), thin(rng)));
  RegularizerConfig no_clamp;
  no_clamp.min_eigen_ratio = 1e-9;
  no_clamp.min_eigenvalue = 1e-12;
  const Distribution d = m.to_distribution(no_clamp);
  EXPECT_NEAR(std::sqrt(d.cov(2, 2)), 0.01, 0.001);
  EXPECT_NEAR(d.cov(0, 0), 1.0 / 3.0, 0.03);
}

/// Point count and sum of points over the whole map, world frame.
struct Totals {
  double count = 0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
};

Totals totals(const VoxelMap& map) {
  Totals t;
  for (const Distribution& d : map.distributions()) {
    t.count += d.count;
    t.sum += d.count * d.mean;
  }
  return t;
}

TEST(VoxelMap, MergingGridVoxelsWithoutCorrectionEqualsRevoting) {
  const PointCloud scan = testing::synthetic_scene(5);
  VoxelizerConfig config;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = so3_exp(Eigen::Vector3d(0, 0, 0.2));
  pose.translation() = Eigen::Vector3d(3.2, -1.1, 0.0);
  Voxelizer voxelizer(config);
  voxelizer.voxelize(scan, pose);
  VoxelMap merged(config, VoxelMapConfig{});
  merged.insert(voxelizer.last_voxels(), pose);
  VoxelMap voted(config, VoxelMapConfig{});
  voted.insert(scan, pose);
  ASSERT_EQ(merged.distributions().size(), voted.distributions().size());
  for (const Distribution& d : voted.distributions()) {
    const int match = merged.find(voxel_index(d.mean, 1.0 / config.voxel_size));
    ASSERT_GE(match, 0);
    const Distribution& m = merged.distributions()[match];
    EXPECT_EQ(m.count, d.count);
    EXPECT_LT((m.mean - d.mean).norm(), 1e-9);
    EXPECT_LT((m.cov - d.cov).norm(), 1e-9);
  }
}

std::vector<Distribution> sorted_by_mean(std::vector<Distribution> distributions) {
  std::sort(distributions.begin(), distributions.end(),
            [](const Distribution& a, const Distribution& b) {
              return std::lexicographical_compare(a.mean.data(), a.mean.data() + 3, b.mean.data(),
                                                  b.mean.data() + 3);
            });
  return distributions;
}

TEST(VoxelMap, AddKeyframeEqualsInsertThenRemoveFar) {
  VoxelizerConfig config;
  VoxelMapConfig map_config;
  map_config.radius = 25.0;  // small, so the second keyframe drops voxels of the first
  VoxelMap separate(config, map_config), combined(config, map_config);
  Voxelizer voxelizer(config);
  for (int k = 0; k < 3; ++k) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = so3_exp(Eigen::Vector3d(0.0, 0.0, 0.1 * k));
    pose.translation() = Eigen::Vector3d(15.0 * k, 2.0 * k, 0.0);
    voxelizer.voxelize(testing::synthetic_scene(5 + k), pose);
    const std::size_t before = separate.num_voxels();
    separate.insert(voxelizer.last_voxels(), pose);
    const std::size_t inserted = separate.num_voxels();
    separate.remove_far(pose.translation());
    if (k > 0) {
      EXPECT_LT(separate.num_voxels(), inserted) << "keyframe " << k << " removed none";
    }
    EXPECT_GT(inserted, before);
    combined.add_keyframe(voxelizer.last_voxels(), pose);
    ASSERT_EQ(combined.num_voxels(), separate.num_voxels());
    // The same distributions; their order is the map's own business (dropped voxels' places
    // are taken by others), so they are compared sorted by mean.
    const std::vector<Distribution> a = sorted_by_mean(combined.distributions());
    const std::vector<Distribution> b = sorted_by_mean(separate.distributions());
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a[i].count, b[i].count);
      EXPECT_EQ(a[i].mean, b[i].mean);
      EXPECT_EQ(a[i].cov, b[i].cov);
    }
  }
}

TEST(VoxelMap, DroppedVoxelsSlotsAreReusedAndEveryDistributionStaysFindable) {
  // A drive along a line with a small radius: each keyframe drops voxels and adds new ones in
  // their slots. Afterwards each distribution is found at its own voxel, each once, and every
  // voxel kept is within the radius.
  VoxelizerConfig config;
  VoxelMapConfig map_config;
  map_config.radius = 20.0;
  VoxelMap map(config, map_config);
  VoxelMap unbounded(config, VoxelMapConfig{1e9});
  Voxelizer voxelizer(config);
  const double inv_size = 1.0 / map.voxel_size();
  for (int k = 0; k < 8; ++k) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = so3_exp(Eigen::Vector3d(0.0, 0.0, 0.05 * k));
    pose.translation() = Eigen::Vector3d(9.0 * k, 1.0 * k, 0.0);
    voxelizer.voxelize(testing::synthetic_scene(k), pose);
    map.add_keyframe(voxelizer.last_voxels(), pose);
    unbounded.add_keyframe(voxelizer.last_voxels(), pose);
    const std::vector<Distribution>& d = map.distributions();
    ASSERT_FALSE(d.empty());
    for (std::size_t i = 0; i < d.size(); ++i) {
      const VoxelIndex index = voxel_index(d[i].mean, inv_size);
      ASSERT_EQ(map.find(index), static_cast<int>(i)) << "keyframe " << k;
      const Eigen::Vector3d centre =
          (index.cast<double>() + Eigen::Vector3d::Constant(0.5)) * map.voxel_size();
      EXPECT_LE((centre - pose.translation()).norm(), map_config.radius);
      EXPECT_GE(d[i].count, config.min_points);
    }
    EXPECT_LE(d.size(), map.num_voxels());
  }
  EXPECT_LT(2 * map.num_voxels(), unbounded.num_voxels()) << "too few voxels were dropped";
}

TEST(VoxelMap, MergingWithCorrectionMovesEveryVoxelExactly) {
  // With a correction, each grid voxel moves whole (boundary points are not re-assigned), so
  // the map's total moments equal those of the points at the final pose.
  const PointCloud scan = testing::synthetic_scene(5);
  VoxelizerConfig config;
  config.min_points = 3;
  Eigen::Isometry3d grid_pose = Eigen::Isometry3d::Identity();
  grid_pose.translation() = Eigen::Vector3d(3.2, -1.1, 0.0);
  Eigen::Isometry3d final_pose = grid_pose;
  final_pose.linear() = so3_exp(Eigen::Vector3d(0.0, 0.0, 0.001));
  final_pose.translation() += Eigen::Vector3d(0.01, -0.005, 0.002);
  Voxelizer voxelizer(config);
  voxelizer.voxelize(scan, grid_pose);
  VoxelMap merged(config, VoxelMapConfig{});
  merged.insert(voxelizer.last_voxels(), final_pose);

  // Expected totals from the points of voxels that reach min_points.
  const Eigen::Isometry3d correction = final_pose * grid_pose.inverse();
  Totals expected;
  for (const VoxelMoments& m : voxelizer.last_voxels().moments) {
    if (m.count < config.min_points) continue;
    expected.count += m.count;
    expected.sum += m.count * (correction * (m.origin + m.sum / m.count));
  }
  const Totals got = totals(merged);
  EXPECT_NEAR(got.count, expected.count, 0.01 * expected.count);  // voxels may merge
  EXPECT_LT((got.sum / got.count - expected.sum / expected.count).norm(), 0.01);
}

TEST(Voxelizer, DistributionsComeBackInTheSensorFrame) {
  const PointCloud scan = testing::synthetic_scene(9);
  Voxelizer voxelizer(VoxelizerConfig{});
  Eigen::Isometry3d grid_pose = Eigen::Isometry3d::Identity();
  grid_pose.linear() = so3_exp(Eigen::Vector3d(0, 0, 1.0));
  grid_pose.translation() = Eigen::Vector3d(100, 50, 2);
  const auto in_sensor = voxelizer.voxelize(scan, grid_pose);
  // Every mean lies inside the sensor-frame bounding box of the scene, not near (100, 50).
  for (const Distribution& d : in_sensor) {
    EXPECT_LT(std::abs(d.mean.x()), 55.0);
    EXPECT_LT(std::abs(d.mean.y()), 30.0);
  }
  EXPECT_GT(in_sensor.size(), 100u);
}

}  // namespace
}  // namespace litamin2

// A tracker that continues another's stream (core/tracker_seed.hpp): a map rebuilt from
// keyframes known by their distributions holds the voxels the grid voxels gave, and the
// continued tracker registers its first scan to it, correcting a wrong prediction, where a
// tracker started at the prediction keeps the error.

#include "litamin2/core/so3.hpp"
#include "litamin2/core/tracker.hpp"
#include "litamin2/core/voxel_key.hpp"
#include "litamin2/core/voxel_map.hpp"
#include "support/s_curve_drive.hpp"
#include "support/synthetic_scene.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace litamin2 {
namespace {

std::vector<Eigen::Isometry3d> path(int frames) {
  return testing::s_curve_path(frames);
}
PointCloud scan_at(const Eigen::Isometry3d& pose, unsigned seed) {
  return testing::scan_seen_from(pose, seed);
}

double translation_error(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.inverse() * b).translation().norm();
}

double angle_error_deg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return Eigen::AngleAxisd((a.inverse() * b).linear()).angle() * 180.0 / M_PI;
}

}  // namespace

TEST(VoxelMapDistributions, KeyframeByItsDistributionsGivesTheGridVoxelsMap) {
  TrackerConfig config;
  Voxelizer voxelizer(config.voxelizer);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = so3_exp(Eigen::Vector3d(0.0, 0.0, 0.3));
  pose.translation() = Eigen::Vector3d(5.0, -2.0, 0.3);
  const PointCloud scan = scan_at(pose, 7);
  const std::vector<Distribution> distributions = voxelizer.voxelize(scan, pose);
  VoxelMap from_voxels(config.voxelizer, config.map);
  from_voxels.add_keyframe(voxelizer.last_voxels(), pose);
  VoxelMap from_distributions(config.voxelizer, config.map);
  from_distributions.add_distributions(distributions, pose);
  ASSERT_GT(from_voxels.distributions().size(), 500u);
  // The scan's voxels were cut in the map's grid at `pose`: every distribution lands in the
  // voxel it came from, with its points' count and mean.
  EXPECT_EQ(from_distributions.distributions().size(), from_voxels.distributions().size());
  const double inv_size = 1.0 / from_voxels.voxel_size();
  std::size_t matched = 0;
  for (const Distribution& d : from_distributions.distributions()) {
    const int i = from_voxels.find(voxel_index(d.mean, inv_size));
    ASSERT_GE(i, 0);
    const Distribution& v = from_voxels.distributions()[static_cast<std::size_t>(i)];
    EXPECT_EQ(d.count, v.count);
    EXPECT_LT((d.mean - v.mean).norm(), 1e-6);
    // The covariance is the lightly regularised one (Distribution::cov): close, not equal.
    EXPECT_LT((d.cov - v.cov).norm(), 0.05 * v.cov.norm() + 1e-4);
    ++matched;
  }
  EXPECT_EQ(matched, from_voxels.distributions().size());
}

TEST(TrackerSeed, ContinuedTrackerRegistersItsFirstScanToTheSeedMap) {
  const auto truth = path(24);
  // The first owner: frames 0..13, its keyframes kept as a map patch carries them.
  TrackerConfig config;
  Tracker first(config);
  std::vector<SeedKeyframe> keyframes;
  std::vector<Eigen::Isometry3d> first_poses;
  for (int i = 0; i < 14; ++i) {
    const FrameResult r = first.process(scan_at(truth[i], 100 + static_cast<unsigned>(i)));
    first_poses.push_back(r.pose);
    if (r.keyframe) {
      const Keyframe k = make_keyframe(first, r, KeyframeKey{"car", keyframes.size()}, Stamp{});
      keyframes.push_back(SeedKeyframe{k.odom_pose, k.voxel_size, k.distributions});
    }
  }
  ASSERT_GE(keyframes.size(), 3u);
  const Eigen::Isometry3d to_first = truth.front().inverse();  // the tracker's frame
  // Frames 14 and 15 are lost (the handover gap); the prediction for frame 16 is wrong by
  // 0.5 m and 2 degrees (an extrapolation error over the gap).
  Eigen::Isometry3d wrong = Eigen::Isometry3d::Identity();
  wrong.linear() = so3_exp(Eigen::Vector3d(0.0, 0.0, 2.0 * M_PI / 180.0));
  wrong.translation() = Eigen::Vector3d(0.4, -0.3, 0.0);
  TrackerSeed seed;
  seed.keyframes.assign(keyframes.end() - 3, keyframes.end());
  seed.predicted = to_first * truth[16] * wrong;
  seed.velocity = first_poses[12].inverse() * first_poses[13];
  seed.interval_s = 0.1;
  Tracker continued(config);
  continued.continue_from(seed);
  // A tracker started at the prediction with no map (the handover without patches).
  Tracker fresh(config);
  TrackerSeed no_map = seed;
  no_map.keyframes.clear();
  fresh.continue_from(no_map);
  for (int i = 16; i < 24; ++i) {
    const PointCloud scan = scan_at(truth[i], 100 + static_cast<unsigned>(i));
    const FrameResult c = continued.process(scan);
    const FrameResult f = fresh.process(scan);
    const Eigen::Isometry3d expected = to_first * truth[i];
    if (i == 16) {
      EXPECT_TRUE(c.registered);   // registered against the seed map at once
      EXPECT_FALSE(f.registered);  // a new map starts with this scan
      EXPECT_EQ(continued.seed_keyframes_used(), 3u);
      EXPECT_EQ(continued.seed_keyframes_skipped(), 0u);
    }
    EXPECT_LT(translation_error(expected, c.pose), 0.10) << "frame " << i;
    EXPECT_LT(angle_error_deg(expected, c.pose), 0.3) << "frame " << i;
    // Without the map the prediction's error stays in every later pose.
    EXPECT_GT(translation_error(expected, f.pose), 0.3) << "frame " << i;
  }
}

TEST(TrackerSeed, KeyframesOfAnotherVoxelSizeAreNotUsedAndSeedingIsBeforeTheFirstScan) {
  const auto truth = path(3);
  TrackerConfig config;
  Tracker first(config);
  const FrameResult r = first.process(scan_at(truth[0], 100));
  const Keyframe k = make_keyframe(first, r, KeyframeKey{"car", 0}, Stamp{});
  TrackerSeed seed;
  seed.keyframes.push_back(SeedKeyframe{k.odom_pose, k.voxel_size * 2.0, k.distributions});
  Tracker continued(config);
  continued.continue_from(seed);
  const FrameResult c = continued.process(scan_at(truth[1], 101));
  EXPECT_EQ(continued.seed_keyframes_used(), 0u);
  EXPECT_EQ(continued.seed_keyframes_skipped(), 1u);
  EXPECT_FALSE(c.registered);
  EXPECT_TRUE(c.keyframe);
  EXPECT_THROW(continued.continue_from(seed), std::logic_error);
}

}  // namespace litamin2

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

#include <algorithm>
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

/// The first owner tracks frames 0..13 of `truth`, its keyframes kept as map patches carry
/// them; frames 14 and 15 are lost (the handover gap). Returns the seed for frame 16 from its
/// last three keyframes and last motion, the prediction `wrong` off (an extrapolation error
/// over the gap), in the tracker's frame (truth.front() at the origin).
TrackerSeed handover_seed(const std::vector<Eigen::Isometry3d>& truth,
                          const Eigen::Isometry3d& wrong) {
  Tracker first{TrackerConfig{}};
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
  EXPECT_GE(keyframes.size(), 3u);
  TrackerSeed seed;
  seed.keyframes.assign(keyframes.end() - std::min<std::ptrdiff_t>(3, keyframes.size()),
                        keyframes.end());
  seed.predicted = truth.front().inverse() * truth[16] * wrong;
  seed.velocity = first_poses[12].inverse() * first_poses[13];
  seed.interval_s = 0.1;
  return seed;
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
  TrackerConfig config;
  const Eigen::Isometry3d to_first = truth.front().inverse();  // the tracker's frame
  // The prediction for frame 16 is wrong by 0.5 m and 2 degrees.
  Eigen::Isometry3d wrong = Eigen::Isometry3d::Identity();
  wrong.linear() = so3_exp(Eigen::Vector3d(0.0, 0.0, 2.0 * M_PI / 180.0));
  wrong.translation() = Eigen::Vector3d(0.4, -0.3, 0.0);
  const TrackerSeed seed = handover_seed(truth, wrong);
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

TEST(TrackerSeed, TheFirstScanAfterAHandoverHasTheCovTermsWiderBasin) {
  // RegistrationConfig::sigma_cov_after_handover: the first scan after a seed is registered
  // with it, every later scan with sigma_cov. Three continued trackers: the defaults (0.3,
  // then 3 after the handover), 3 throughout, and 0.3 throughout.
  const auto truth = path(24);
  TrackerConfig config;
  const Eigen::Isometry3d to_first = truth.front().inverse();
  // The prediction over the gap is 1.5 m and 6 degrees off.
  Eigen::Isometry3d wrong = Eigen::Isometry3d::Identity();
  wrong.linear() = so3_exp(Eigen::Vector3d(0.0, 0.0, 6.0 * M_PI / 180.0));
  wrong.translation() = Eigen::Vector3d(1.2, -0.9, 0.0);
  const TrackerSeed seed = handover_seed(truth, wrong);
  ASSERT_NE(config.registration.sigma_cov, config.registration.sigma_cov_after_handover);
  TrackerConfig strong_config = config;
  strong_config.registration.sigma_cov = config.registration.sigma_cov_after_handover;
  TrackerConfig weak_config = config;
  weak_config.registration.sigma_cov_after_handover = 0.0;
  Tracker by_default(config), strong(strong_config), weak(weak_config);
  for (Tracker* t : {&by_default, &strong, &weak}) t->continue_from(seed);
  for (int i = 16; i < 19; ++i) {
    const PointCloud scan = scan_at(truth[i], 100 + static_cast<unsigned>(i));
    const FrameResult d = by_default.process(scan);
    const FrameResult s = strong.process(scan);
    const FrameResult w = weak.process(scan);
    const Eigen::Isometry3d expected = to_first * truth[i];
    EXPECT_LT(translation_error(expected, d.pose), 0.10) << "frame " << i;
    EXPECT_LT(angle_error_deg(expected, d.pose), 0.3) << "frame " << i;
    if (i == 16) {
      // The handover's scan: registered as with 3 throughout, bit for bit.
      EXPECT_TRUE(d.pose.isApprox(s.pose, 0.0)) << "frame " << i;
      EXPECT_FALSE(d.pose.isApprox(w.pose, 0.0)) << "frame " << i;
    } else if (i == 18) {
      // Later scans: sigma_cov, not 3.
      EXPECT_FALSE(d.pose.isApprox(s.pose, 0.0)) << "frame " << i;
    }
    std::printf(
        "frame %d: defaults %.4f m %.3f deg; 3 throughout %.4f m; 0.3 throughout %.4f m "
        "%.3f deg\n",
        i, translation_error(expected, d.pose), angle_error_deg(expected, d.pose),
        translation_error(expected, s.pose), translation_error(expected, w.pose),
        angle_error_deg(expected, w.pose));
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

// The tracker along a known path through a synthetic scene: accuracy, determinism across
// thread counts, bounded map, and recovery from an unregistrable frame.

#include "litamin2/core/so3.hpp"
#include "litamin2/core/tracker.hpp"
#include "support/s_curve_drive.hpp"
#include "support/synthetic_scene.hpp"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstring>

namespace litamin2 {
namespace {

std::vector<Eigen::Isometry3d> path(int frames) {
  return testing::s_curve_path(frames);
}
PointCloud scan_at(const Eigen::Isometry3d& pose, unsigned seed) {
  return testing::scan_seen_from(pose, seed);
}

std::vector<Eigen::Isometry3d> run(const std::vector<Eigen::Isometry3d>& truth, CostMode mode) {
  TrackerConfig config;
  config.registration.mode = mode;
  Tracker tracker(config);
  std::vector<Eigen::Isometry3d> poses;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    poses.push_back(tracker.process(scan_at(truth[i], 100 + static_cast<unsigned>(i))).pose);
  }
  return poses;
}

class TrackerTest : public ::testing::TestWithParam<CostMode> {};

TEST_P(TrackerTest, FollowsKnownPath) {
  const auto truth = path(30);
  const auto poses = run(truth, GetParam());
  const Eigen::Isometry3d origin = truth.front().inverse();
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const Eigen::Isometry3d error = (origin * truth[i]).inverse() * poses[i];
    EXPECT_LT(error.translation().norm(), 0.10) << "frame " << i;
    EXPECT_LT(Eigen::AngleAxisd(error.linear()).angle() * 180.0 / M_PI, 0.3) << "frame " << i;
  }
}

INSTANTIATE_TEST_SUITE_P(Modes, TrackerTest, ::testing::Values(CostMode::kIcp, CostMode::kIcpCov));

TEST(Tracker, BitIdenticalPosesForAnyThreadCount) {
  const auto truth = path(12);
  std::vector<Eigen::Isometry3d> reference;
  tbb::task_arena(1).execute([&] { reference = run(truth, CostMode::kIcpCov); });
  for (int threads : {2, 4}) {
    std::vector<Eigen::Isometry3d> poses;
    tbb::task_arena(threads).execute([&] { poses = run(truth, CostMode::kIcpCov); });
    ASSERT_EQ(poses.size(), reference.size());
    for (std::size_t i = 0; i < poses.size(); ++i) {
      EXPECT_EQ(0, std::memcmp(poses[i].matrix().data(), reference[i].matrix().data(),
                               16 * sizeof(double)))
          << threads << " threads, frame " << i;
    }
  }
}

TEST(Tracker, MapStaysWithinRadius) {
  // 40 frames cover 32 m: with a 15 m radius the map must drop what lies behind, which a map
  // without eviction (radius 1000 m) keeps.
  const auto truth = path(40);
  const Eigen::Vector3d here = (truth.front().inverse() * truth.back()).translation();
  auto farthest = [&](double radius) {
    TrackerConfig config;
    config.map.radius = radius;
    Tracker tracker(config);
    for (std::size_t i = 0; i < truth.size(); ++i) tracker.process(scan_at(truth[i], 7));
    EXPECT_FALSE(tracker.map().distributions().empty());
    double farthest = 0.0;
    for (const Distribution& d : tracker.map().distributions())
      farthest = std::max(farthest, (d.mean - here).norm());
    return farthest;
  };
  const double voxel = TrackerConfig().voxelizer.voxel_size;
  EXPECT_GT(farthest(1000.0), 15.0 + voxel);
  EXPECT_LT(farthest(15.0), 15.0 + voxel);
}

TEST(Tracker, EmptyScanDoesNotBreakTracking) {
  Tracker tracker(TrackerConfig{});
  const auto truth = path(8);
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const FrameResult frame = tracker.process(i == 4 ? PointCloud{} : scan_at(truth[i], 3));
    if (i == 4) {
      EXPECT_FALSE(frame.registered);
    } else if (i > 4) {
      EXPECT_TRUE(frame.registered) << "frame " << i;
    }
  }
}

}  // namespace
}  // namespace litamin2

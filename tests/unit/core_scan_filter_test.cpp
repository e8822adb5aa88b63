// Self-hit filtering: the ego box drops exactly the points inside it, and the learnt ego cells
// (EgoFilterMode::kAuto) are the sensor-frame cells that are hit in every scan.

#include "litamin2/core/scan_filter.hpp"
#include "litamin2/core/tracker.hpp"
#include "support/synthetic_scene.hpp"

#include <gtest/gtest.h>

#include <random>

namespace litamin2 {
namespace {

/// A scan of the synthetic scene seen from `pose`, plus `body` points on a box behind the
/// sensor (x -1.8..-0.8, |y| < 0.6, z -0.4..-0.1) that move with it.
PointCloud scan_with_body(const Eigen::Isometry3d& pose, unsigned seed, int body) {
  PointCloud scan = testing::transformed(testing::synthetic_scene(seed, 30000), pose.inverse());
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < body; ++i)
    scan.points.emplace_back(-1.8f + u(rng), -0.6f + 1.2f * u(rng), -0.4f + 0.3f * u(rng));
  return scan;
}

bool in_body(const Eigen::Vector3f& p) {
  return p.x() > -1.8f && p.x() < -0.8f && std::abs(p.y()) < 0.6f && p.z() > -0.4f && p.z() < -0.1f;
}

TEST(ScanFilter, BoxDropsExactlyThePointsInside) {
  PointCloud scan = scan_with_body(Eigen::Isometry3d::Identity(), 3, 500);
  scan.intensities.assign(scan.points.size(), 0.0f);
  for (std::size_t i = 0; i < scan.points.size(); ++i) scan.intensities[i] = float(i);
  PointCloud out;
  remove_box(scan, Eigen::Vector3d(-1.8, -0.6, -0.4), Eigen::Vector3d(-0.8, 0.6, -0.1), out);
  std::size_t inside = 0;
  for (const auto& p : scan.points) inside += in_body(p) ? 1 : 0;
  EXPECT_GE(inside, 500u);
  EXPECT_EQ(out.points.size(), scan.points.size() - inside);
  ASSERT_EQ(out.intensities.size(), out.points.size());
  for (std::size_t i = 0; i < out.points.size(); ++i) {
    EXPECT_FALSE(in_body(out.points[i]));
    EXPECT_EQ(out.points[i], scan.points[static_cast<std::size_t>(out.intensities[i])]);
  }
}

TEST(ScanFilter, LearnsTheCellsHitInEveryScan) {
  ScanFilterConfig config;
  EgoLearner learner(config);
  PointCloud out;
  for (int i = 0; i < config.auto_scans; ++i) {
    const PointCloud scan =
        scan_with_body(testing::planar_pose(-10.0 + 1.5 * i, 0.0, 2.0 * i), 10 + i, 400);
    EXPECT_FALSE(learner.decided());
    EXPECT_FALSE(learner.filter(scan, out));
    learner.observe(scan);
  }
  ASSERT_TRUE(learner.decided());
  EXPECT_GT(learner.cells(), 0u);
  const PointCloud next = scan_with_body(testing::planar_pose(5.0, 1.0, 20.0), 99, 400);
  ASSERT_TRUE(learner.filter(next, out));
  std::size_t body_left = 0, world_dropped = 0;
  for (const auto& p : out.points) body_left += in_body(p) ? 1 : 0;
  for (const auto& p : next.points)
    if (!in_body(p) && learner.is_ego(p)) ++world_dropped;
  // Cells straddling the body's boundary keep a few body points; no world point is dropped.
  EXPECT_LT(body_left, 40u);
  EXPECT_EQ(world_dropped, 0u);
}

TEST(ScanFilter, TrackerReportsTheSelfHitsItDrops) {
  TrackerConfig config;
  config.filter.ego = EgoFilterMode::kBox;
  config.filter.ego_box_min = Eigen::Vector3d(-1.8, -0.6, -0.4);
  config.filter.ego_box_max = Eigen::Vector3d(-0.8, 0.6, -0.1);
  Tracker tracker(config);
  const FrameResult frame = tracker.process(scan_with_body(Eigen::Isometry3d::Identity(), 5, 300));
  EXPECT_GE(frame.self_hits, 300);
  config.filter.ego_box_max.x() = -1.9;  // min not below max
  EXPECT_THROW(Tracker{config}, ConfigError);
}

}  // namespace
}  // namespace litamin2

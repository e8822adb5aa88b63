#include "litamin2/eval/kitti_metrics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace le = litamin2::eval;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegToRad = kPi / 180.0;

// Straight line along the camera z axis, one pose per metre, identity rotations.
std::vector<Eigen::Isometry3d> straight_line(int frames) {
  std::vector<Eigen::Isometry3d> poses;
  for (int i = 0; i < frames; ++i) {
    Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
    p.translation() = Eigen::Vector3d(0.0, 0.0, static_cast<double>(i));
    poses.push_back(p);
  }
  return poses;
}

// A winding, slightly hilly trajectory: integrates 0.8 m steps along a varying heading.
std::vector<Eigen::Isometry3d> curved_trajectory(int frames) {
  std::vector<Eigen::Isometry3d> poses;
  Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
  for (int i = 0; i < frames; ++i) {
    poses.push_back(p);
    Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
    step.linear() = (Eigen::AngleAxisd(0.02 * std::sin(0.01 * i), Eigen::Vector3d::UnitY()) *
                     Eigen::AngleAxisd(0.002 * std::cos(0.03 * i), Eigen::Vector3d::UnitX()))
                        .toRotationMatrix();
    step.translation() = Eigen::Vector3d(0.0, 0.0, 0.8);
    p = p * step;
  }
  return poses;
}

// Mean of (len + offset) / len over every devkit segment of a straight 1 m/frame line.
double mean_length_ratio(int frames, int offset) {
  double sum = 0.0;
  int count = 0;
  for (int first = 0; first < frames; first += 10) {
    for (int len = 100; len <= 800; len += 100) {
      if (first + len + offset >= frames) continue;
      sum += static_cast<double>(len + offset) / len;
      ++count;
    }
  }
  return sum / count;
}

}  // namespace

TEST(EvalKittiMetrics, TrajectoryDistancesAccumulatePathLength) {
  const auto poses = straight_line(5);
  const auto dist = le::trajectory_distances(poses);
  ASSERT_EQ(dist.size(), 5u);
  EXPECT_EQ(dist[0], 0.0);
  EXPECT_EQ(dist[4], 4.0);
  EXPECT_TRUE(le::trajectory_distances({}).empty());
}

TEST(EvalKittiMetrics, LastFrameFollowsDevkitStrictComparison) {
  const auto dist = le::trajectory_distances(straight_line(301));
  // Devkit: first frame with dist > dist[first] + len.
  EXPECT_EQ(le::last_frame_from_segment_length(dist, 0, 100.0), std::optional<std::size_t>(101));
  EXPECT_EQ(le::last_frame_from_segment_length(dist, 0, 100.0, false),
            std::optional<std::size_t>(100));
  EXPECT_EQ(le::last_frame_from_segment_length(dist, 200, 100.0), std::nullopt);
  EXPECT_EQ(le::last_frame_from_segment_length(dist, 200, 100.0, false),
            std::optional<std::size_t>(300));
  EXPECT_EQ(le::last_frame_from_segment_length(dist, 400, 1.0), std::nullopt);
}

TEST(EvalKittiMetrics, IdenticalTrajectoriesGiveExactlyZero) {
  const auto gt = curved_trajectory(1500);
  const le::KittiMetrics m = le::compute_kitti_metrics(gt, gt);
  ASSERT_TRUE(m.valid());
  EXPECT_GT(m.segments, 500u);
  EXPECT_EQ(m.translation_percent, 0.0);
  EXPECT_EQ(m.rotation_deg_per_100m, 0.0);
  for (const auto& s : m.segment_errors) {
    EXPECT_EQ(s.translation_error, 0.0);
    EXPECT_EQ(s.rotation_error, 0.0);
  }
  ASSERT_EQ(m.per_length.size(), 8u);
  for (const auto& l : m.per_length) {
    EXPECT_GT(l.segments, 0u);
    EXPECT_EQ(l.translation_percent, 0.0);
    EXPECT_EQ(l.rotation_deg_per_100m, 0.0);
  }
}

TEST(EvalKittiMetrics, ScaledStraightLineGivesOnePercent) {
  const auto gt = straight_line(1001);
  auto est = gt;
  for (auto& p : est) p.translation() *= 1.01;

  le::KittiMetricsOptions inclusive;
  inclusive.strict_segment_end = false;  // segment ends exactly at len: error is exactly 1 %
  const le::KittiMetrics m = le::compute_kitti_metrics(gt, est, inclusive);
  ASSERT_TRUE(m.valid());
  EXPECT_NEAR(m.translation_percent, 1.0, 1e-6);
  EXPECT_EQ(m.rotation_deg_per_100m, 0.0);
  for (const auto& l : m.per_length) EXPECT_NEAR(l.translation_percent, 1.0, 1e-6);
  // Starts 0, 10, ..., 1000 with first + len <= 1000: sum over len of (1000 - len) / 10 + 1.
  EXPECT_EQ(m.segments, 8u * 101u - (10u + 20u + 30u + 40u + 50u + 60u + 70u + 80u));

  // Devkit comparison (strict >): each segment is len + 1 m long but divided by len.
  const le::KittiMetrics devkit = le::compute_kitti_metrics(gt, est);
  EXPECT_NEAR(devkit.translation_percent, mean_length_ratio(1001, 1), 1e-9);
  EXPECT_EQ(devkit.rotation_deg_per_100m, 0.0);
  EXPECT_NEAR(devkit.per_length[0].translation_percent, 1.01, 1e-9);
  EXPECT_NEAR(devkit.per_length[7].translation_percent, 801.0 / 800.0, 1e-9);
}

TEST(EvalKittiMetrics, ConstantYawRateErrorGivesClosedFormRotationError) {
  // Estimate yaws (about the camera y axis) 1 degree per 100 m = 0.01 degree per frame.
  const double rate = 0.01 * kDegToRad;
  const auto gt = straight_line(1001);
  auto est = gt;
  for (std::size_t i = 0; i < est.size(); ++i) {
    est[i].linear() = Eigen::AngleAxisd(rate * i, Eigen::Vector3d::UnitY()).toRotationMatrix();
  }

  le::KittiMetricsOptions inclusive;
  inclusive.strict_segment_end = false;
  const le::KittiMetrics m = le::compute_kitti_metrics(gt, est, inclusive);
  ASSERT_TRUE(m.valid());
  EXPECT_NEAR(m.rotation_deg_per_100m, 1.0, 1e-9);
  for (const auto& l : m.per_length) EXPECT_NEAR(l.rotation_deg_per_100m, 1.0, 1e-9);
  EXPECT_GT(m.translation_percent, 0.0);

  const le::KittiMetrics devkit = le::compute_kitti_metrics(gt, est);
  EXPECT_NEAR(devkit.rotation_deg_per_100m, mean_length_ratio(1001, 1), 1e-9);
}

TEST(EvalKittiMetrics, SegmentsStartEveryTenFramesWithDevkitSpeed) {
  const auto gt = straight_line(1001);
  const le::KittiMetrics m = le::compute_kitti_metrics(gt, gt);
  ASSERT_FALSE(m.segment_errors.empty());
  for (const auto& s : m.segment_errors) {
    EXPECT_EQ(s.first_frame % 10, 0u);
    EXPECT_EQ(s.last_frame, s.first_frame + static_cast<std::size_t>(s.length) + 1);
    EXPECT_DOUBLE_EQ(s.speed, s.length / (0.1 * (s.last_frame - s.first_frame + 1)));
  }
  EXPECT_EQ(m.segment_errors.front().first_frame, 0u);
  EXPECT_EQ(m.segment_errors.front().length, 100.0);
}

TEST(EvalKittiMetrics, TrajectoryShorterThan100mIsUndefined) {
  const auto gt = straight_line(90);  // 89 m
  auto est = gt;
  for (auto& p : est) p.translation() *= 1.05;
  const le::KittiMetrics m = le::compute_kitti_metrics(gt, est);
  EXPECT_FALSE(m.valid());
  EXPECT_EQ(m.segments, 0u);
  EXPECT_TRUE(m.segment_errors.empty());
  EXPECT_TRUE(std::isnan(m.translation_percent));
  EXPECT_TRUE(std::isnan(m.rotation_deg_per_100m));
  ASSERT_EQ(m.per_length.size(), 8u);
  for (const auto& l : m.per_length) {
    EXPECT_EQ(l.segments, 0u);
    EXPECT_TRUE(std::isnan(l.translation_percent));
  }
  EXPECT_EQ(le::compute_kitti_metrics({}, {}).segments, 0u);
}

TEST(EvalKittiMetrics, SizeMismatchThrows) {
  const auto gt = straight_line(200);
  const auto est = straight_line(199);
  EXPECT_THROW(le::compute_kitti_metrics(gt, est), std::invalid_argument);
}

// KITTI metric and ATE on the real ground truth of KITTI odometry sequence 07, compared with
// copies perturbed by known drifts. Skipped when the shared data set is absent.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "litamin2/eval/ate.hpp"
#include "litamin2/eval/kitti_metrics.hpp"
#include "litamin2/eval/relative_error.hpp"
#include "litamin2/io/trajectory.hpp"

namespace le = litamin2::eval;

namespace {

constexpr double kPi = 3.14159265358979323846;

std::vector<Eigen::Isometry3d> load_07() {
  const std::string path = std::string(LITAMIN2_SHARED_DATA_DIR) + "/kitti/poses/07.txt";
  if (!std::ifstream(path).good()) return {};
  return litamin2::io::read_kitti_poses(path);
}

}  // namespace

TEST(EvalKitti07, SelfComparisonIsZero) {
  const auto gt = load_07();
  if (gt.empty()) GTEST_SKIP() << "kitti/poses/07.txt not available";
  ASSERT_EQ(gt.size(), 1101u);
  const le::KittiMetrics m = le::compute_kitti_metrics(gt, gt);
  ASSERT_TRUE(m.valid());
  EXPECT_EQ(m.translation_percent, 0.0);
  EXPECT_EQ(m.rotation_deg_per_100m, 0.0);
  // 07 is about 695 m long: 700 m and 800 m segments do not exist.
  EXPECT_GT(m.per_length[5].segments, 0u);
  EXPECT_EQ(m.per_length[6].segments, 0u);
  EXPECT_EQ(m.per_length[7].segments, 0u);
}

TEST(EvalKitti07, ScaleDriftGivesHalfPercent) {
  const auto gt = load_07();
  if (gt.empty()) GTEST_SKIP() << "kitti/poses/07.txt not available";
  auto est = gt;
  for (auto& p : est) p.translation() *= 1.005;  // 0.5 % too long everywhere
  const le::KittiMetrics m = le::compute_kitti_metrics(gt, est);
  ASSERT_TRUE(m.valid());
  // Segment error = 0.005 * chord / len; the chord is at most the path (slightly > len).
  EXPECT_GT(m.translation_percent, 0.3);
  EXPECT_LT(m.translation_percent, 0.51);
  EXPECT_EQ(m.rotation_deg_per_100m, 0.0);
  for (const auto& s : m.segment_errors) EXPECT_LT(s.translation_error * 100.0, 0.52);

  const le::AteResult ate = le::compute_ate(gt, est);
  EXPECT_GT(ate.translation_rmse, 0.1);
  EXPECT_LT(ate.translation_rmse, 0.005 * 700.0);
}

TEST(EvalKitti07, YawDriftGivesExpectedRotationError) {
  const auto gt = load_07();
  if (gt.empty()) GTEST_SKIP() << "kitti/poses/07.txt not available";
  // Re-integrate the true frame-to-frame motions with 0.001 degree extra yaw per frame.
  const double eps = 0.001 * kPi / 180.0;
  const Eigen::Isometry3d yaw(Eigen::AngleAxisd(eps, Eigen::Vector3d::UnitY()));
  std::vector<Eigen::Isometry3d> est{gt.front()};
  for (std::size_t i = 1; i < gt.size(); ++i) {
    est.push_back(est.back() * le::relative_motion(gt[i - 1], gt[i]) * yaw);
  }
  const le::KittiMetrics m = le::compute_kitti_metrics(gt, est);
  ASSERT_TRUE(m.valid());
  // KITTI frames turn mostly about the camera y axis, so the extra yaws add up:
  // expected r_err of a segment ~ eps * (last - first) / len.
  double expected = 0.0;
  for (const auto& s : m.segment_errors) {
    expected += eps * static_cast<double>(s.last_frame - s.first_frame) / s.length;
  }
  expected *= 100.0 * 180.0 / kPi / static_cast<double>(m.segments);
  EXPECT_NEAR(m.rotation_deg_per_100m, expected, 0.05 * expected);
  EXPECT_GT(m.rotation_deg_per_100m, 0.05);
  EXPECT_LT(m.rotation_deg_per_100m, 1.0);
  EXPECT_GT(m.translation_percent, 0.01);
  EXPECT_LT(m.translation_percent, 5.0);

  const le::AteResult ate = le::compute_ate(gt, est);
  EXPECT_GT(ate.translation_rmse, 0.01);
  EXPECT_GT(ate.rotation_rmse_deg, 0.0);
}

TEST(EvalKitti07, RigidlyMovedCopyHasZeroAte) {
  const auto gt = load_07();
  if (gt.empty()) GTEST_SKIP() << "kitti/poses/07.txt not available";
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() =
      Eigen::AngleAxisd(0.5, Eigen::Vector3d(0.1, 1.0, 0.2).normalized()).toRotationMatrix();
  t.translation() = Eigen::Vector3d(100.0, -2.0, 30.0);
  std::vector<Eigen::Isometry3d> est;
  for (const auto& p : gt) est.push_back(t * p);
  const le::AteResult ate = le::compute_ate(gt, est);
  EXPECT_LT(ate.translation_rmse, 1e-6);
  EXPECT_LT(ate.rotation_rmse_deg, 1e-4);
  EXPECT_TRUE(ate.alignment.inverse().matrix().isApprox(t.matrix(), 1e-6));
  // The KITTI metric is invariant to a common rigid transform of the estimate.
  const le::KittiMetrics m = le::compute_kitti_metrics(gt, est);
  EXPECT_LT(m.translation_percent, 1e-6);
  EXPECT_LT(m.rotation_deg_per_100m, 1e-3);
}

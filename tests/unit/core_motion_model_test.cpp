// The tracker's constant-velocity motion model (core/motion_model.hpp): a motion scaled to
// another interval, and the interval ratio with its cap.

#include "litamin2/core/motion_model.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace litamin2 {
namespace {

Eigen::Isometry3d motion(double yaw, const Eigen::Vector3d& t) {
  Eigen::Isometry3d m = Eigen::Isometry3d::Identity();
  m.linear() =
      Eigen::AngleAxisd(yaw, Eigen::Vector3d(0.1, -0.2, 1.0).normalized()).toRotationMatrix();
  m.translation() = t;
  return m;
}

TEST(MotionModel, ScalingMultipliesTheAngleAndTheTranslation) {
  const Eigen::Isometry3d m = motion(0.05, Eigen::Vector3d(2.5, -0.3, 0.1));
  const Eigen::Isometry3d twice = scaled_motion(m, 2.0);
  const Eigen::AngleAxisd a(m.linear()), b(twice.linear());
  EXPECT_NEAR(b.angle(), 2.0 * a.angle(), 1e-12);
  EXPECT_NEAR((b.axis() - a.axis()).norm(), 0.0, 1e-9);
  EXPECT_NEAR((twice.translation() - 2.0 * m.translation()).norm(), 0.0, 1e-12);
  // Scaled twice by 2 is the same rotation as the motion applied twice.
  EXPECT_NEAR((twice.linear() - m.linear() * m.linear()).norm(), 0.0, 1e-12);
  // 1 is the motion itself, 0 no motion.
  EXPECT_NEAR((scaled_motion(m, 1.0).matrix() - m.matrix()).norm(), 0.0, 1e-12);
  EXPECT_NEAR((scaled_motion(m, 0.0).matrix() - Eigen::Matrix4d::Identity()).norm(), 0.0, 1e-12);
  // No rotation stays no rotation.
  const Eigen::Isometry3d straight = scaled_motion(motion(0.0, Eigen::Vector3d(1, 0, 0)), 3.0);
  EXPECT_NEAR((straight.linear() - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-12);
  EXPECT_NEAR(straight.translation().x(), 3.0, 1e-12);
}

TEST(MotionModel, IntervalRatioIsCappedAndNeutralWhenUnknown) {
  EXPECT_DOUBLE_EQ(interval_ratio(0.3, 0.1, 5.0), 3.0);
  EXPECT_DOUBLE_EQ(interval_ratio(0.05, 0.1, 5.0), 0.5);
  EXPECT_DOUBLE_EQ(interval_ratio(1.0, 0.1, 5.0), 5.0);  // a long gap: at most the cap
  EXPECT_DOUBLE_EQ(interval_ratio(0.0, 0.1, 5.0), 1.0);  // no interval (first scan, new clock)
  EXPECT_DOUBLE_EQ(interval_ratio(0.1, 0.0, 5.0), 1.0);  // no previous interval
  EXPECT_DOUBLE_EQ(interval_ratio(std::nan(""), 0.1, 5.0), 1.0);
}

}  // namespace
}  // namespace litamin2

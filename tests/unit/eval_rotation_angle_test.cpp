#include "litamin2/eval/rotation_angle.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>

namespace le = litamin2::eval;

TEST(EvalRotationAngle, MatchesAngleAxisAndDevkitFormula) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(0.01, 3.1);
  std::normal_distribution<double> gauss;
  for (int k = 0; k < 200; ++k) {
    const Eigen::Vector3d axis = Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)).normalized();
    const double a = angle(rng);
    const Eigen::Matrix3d r = Eigen::AngleAxisd(a, axis).toRotationMatrix();
    EXPECT_NEAR(le::rotation_angle(r), a, 1e-9);
    // KITTI devkit: acos(max(min(0.5 * (trace - 1), 1), -1)).
    const double devkit = std::acos(std::max(std::min(0.5 * (r.trace() - 1.0), 1.0), -1.0));
    EXPECT_NEAR(le::rotation_angle(r), devkit, 1e-7);
  }
}

TEST(EvalRotationAngle, RelativeAngleAndExactZero) {
  const Eigen::Matrix3d a =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Matrix3d b =
      a * Eigen::AngleAxisd(0.25, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_NEAR(le::rotation_angle_between(a, b), 0.25, 1e-12);
  EXPECT_NEAR(le::rotation_angle_between(b, a), 0.25, 1e-12);
  EXPECT_EQ(le::rotation_angle_between(a, a), 0.0);
  EXPECT_EQ(le::rotation_angle(Eigen::Matrix3d::Identity()), 0.0);
  // Tiny angle: accurate where acos would lose half of the digits.
  const Eigen::Matrix3d tiny = Eigen::AngleAxisd(1e-9, Eigen::Vector3d::UnitX()).toRotationMatrix();
  EXPECT_NEAR(le::rotation_angle(tiny), 1e-9, 1e-15);
  const Eigen::Matrix3d half_turn =
      Eigen::AngleAxisd(3.14159265358979323846, Eigen::Vector3d::UnitY()).toRotationMatrix();
  EXPECT_NEAR(le::rotation_angle(half_turn), 3.14159265358979323846, 1e-9);
}

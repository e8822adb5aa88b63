// SO(3)/SE(3) helpers: the left update, the adjoint and the covariance it moves, checked against
// the definitions numerically (a wrong sign or block would fail).

#include "litamin2/core/so3.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace litamin2 {
namespace {

Eigen::Isometry3d some_pose() {
  Eigen::Isometry3d e = Eigen::Isometry3d::Identity();
  e.linear() = (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()) *
                Eigen::AngleAxisd(-0.4, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  e.translation() = Eigen::Vector3d(1.5, -2.0, 0.8);
  return e;
}

/// The left update as a transform: (exp([phi]x), tau).
Eigen::Isometry3d update(const Vector6d& xi) {
  return apply_left_update(xi, Eigen::Isometry3d::Identity());
}

TEST(Se3, AdjointConjugatesTheLeftUpdate) {
  // E exp(xi) E^-1 = exp(Ad_E xi): checked for small increments, where the left update
  // (exp([phi]x), tau) and the SE(3) exponential agree to first order.
  const Eigen::Isometry3d e = some_pose();
  const Matrix6d ad = adjoint(e);
  for (int k = 0; k < 6; ++k) {
    Vector6d xi = Vector6d::Zero();
    xi(k) = 1e-6;
    const Eigen::Isometry3d conjugated = e * update(xi) * e.inverse();
    const Eigen::Isometry3d mapped = update(ad * xi);
    EXPECT_TRUE(conjugated.matrix().isApprox(mapped.matrix(), 1e-11)) << "axis " << k;
    // The same for E exp(xi) T with any T on the right.
    const Eigen::Isometry3d t = some_pose().inverse();
    EXPECT_TRUE((e * update(xi) * t).matrix().isApprox((update(ad * xi) * e * t).matrix(), 1e-11));
  }
}

TEST(Se3, TransformLeftCovarianceIsTheAdjointTransform) {
  Matrix6d c = Matrix6d::Zero();
  c.diagonal() << 1, 2, 3, 4, 5, 6;
  Eigen::Isometry3d e = Eigen::Isometry3d::Identity();
  EXPECT_TRUE(transform_left_covariance(c, e).isApprox(c));
  e.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Matrix6d rotated = transform_left_covariance(c, e);
  // A quarter turn about z swaps the x and y variances of both blocks.
  EXPECT_NEAR(rotated(0, 0), 2, 1e-12);
  EXPECT_NEAR(rotated(1, 1), 1, 1e-12);
  EXPECT_NEAR(rotated(3, 3), 5, 1e-12);
  EXPECT_NEAR(rotated(4, 4), 4, 1e-12);
  // A translated sensor: rotation uncertainty about the sensor moves the base.
  e = Eigen::Isometry3d::Identity();
  e.translation() = Eigen::Vector3d(2, 0, 0);
  Matrix6d yaw_only = Matrix6d::Zero();
  yaw_only(2, 2) = 0.01;
  const Matrix6d moved = transform_left_covariance(yaw_only, e);
  EXPECT_NEAR(moved(4, 4), 0.04, 1e-12);  // y variance = (lever 2 m)^2 * 0.01
}

TEST(Se3, SkewAndVeeAreInverse) {
  const Eigen::Vector3d v(0.3, -1.2, 2.5), w(-0.7, 0.4, 1.1);
  EXPECT_TRUE((skew(v) * w).isApprox(v.cross(w)));
  EXPECT_TRUE(vee(skew(v)).isApprox(v));
}

}  // namespace
}  // namespace litamin2

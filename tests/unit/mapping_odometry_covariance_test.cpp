// The odometry edge's covariance from the tracker's (mapping/odometry_covariance.hpp): the
// Jacobian from b's left update to the relative pose's residual coordinates, checked against
// the relative pose actually perturbed (a wrong sign, inverse or frame fails), and a pose graph
// that weights an edge's directions by its full covariance.

#include "litamin2/core/so3.hpp"
#include "litamin2/mapping/odometry_covariance.hpp"
#include "litamin2/mapping/pose_graph.hpp"

#include "support/poses.hpp"

#include <gtest/gtest.h>

using namespace litamin2;
using namespace litamin2::mapping;

namespace {

using litamin2::testing::pose_of;

/// The residual coordinates of T_ab' relative to T_ab, as pose_graph.cpp defines them:
/// translation difference in a's frame, rotation of T_ab^-1 T_ab' as a rotation vector.
Vector6d residual_coordinates(const Eigen::Isometry3d& t_ab, const Eigen::Isometry3d& perturbed) {
  Vector6d e;
  e.head<3>() = perturbed.translation() - t_ab.translation();
  const Eigen::AngleAxisd aa(t_ab.linear().transpose() * perturbed.linear());
  e.tail<3>() = aa.angle() * aa.axis();
  return e;
}

}  // namespace

TEST(MappingOdometryCovariance, MatchesThePerturbedRelativePose) {
  // Far from the origin and turned, so that the lever arm [t_b]x phi and both rotations matter.
  const Eigen::Isometry3d a = pose_of(120.0, -45.0, 3.0, 0.05, -0.03, 2.1);
  const Eigen::Isometry3d b = a * pose_of(1.8, 0.3, 0.05, 0.01, 0.02, 0.15);
  const Eigen::Isometry3d t_ab = a.inverse() * b;
  for (int k = 0; k < 6; ++k) {
    // A rank-one covariance xi xi^T must map to e e^T, e the residual of b moved by xi.
    Vector6d xi = Vector6d::Zero();
    xi(k) = 1e-6;
    xi((k + 2) % 6) = -0.7e-6;
    const Matrix6d c = relative_pose_covariance(a, b, xi * xi.transpose());
    const Vector6d e = residual_coordinates(t_ab, a.inverse() * apply_left_update(xi, b));
    const Matrix6d expected = e * e.transpose();
    EXPECT_LT((c - expected).norm(), 1e-4 * expected.norm()) << "component " << k << "\n"
                                                             << c << "\nvs\n"
                                                             << expected;
  }
}

TEST(MappingOdometryCovariance, IsotropicRotationAtTheOriginOnlyReorders) {
  // a = identity, b at the origin: J = [[0, I], [R_b^T, 0]]: the tau block becomes the
  // translation block, phi rotated into b's frame becomes the rotation block.
  Matrix6d left = Matrix6d::Zero();
  left.topLeftCorner<3, 3>() = Eigen::Vector3d(1e-4, 2e-4, 3e-4).asDiagonal();
  left.bottomRightCorner<3, 3>() = Eigen::Vector3d(4e-2, 5e-2, 6e-2).asDiagonal();
  const Eigen::Isometry3d b = pose_of(0, 0, 0, 0, 0, M_PI / 2);
  const Matrix6d c = relative_pose_covariance(Eigen::Isometry3d::Identity(), b, left);
  EXPECT_NEAR(c(0, 0), 4e-2, 1e-12);
  EXPECT_NEAR(c(2, 2), 6e-2, 1e-12);
  // A yaw of 90 deg swaps the x and y rotation variances in b's frame.
  EXPECT_NEAR(c(3, 3), 2e-4, 1e-12);
  EXPECT_NEAR(c(4, 4), 1e-4, 1e-12);
  EXPECT_NEAR(c(5, 5), 3e-4, 1e-12);
  const double off_diagonal = c.topRightCorner<3, 3>().norm();
  EXPECT_NEAR(off_diagonal, 0.0, 1e-15);
}

TEST(MappingOdometryCovariance, PoseGraphWeighsEdgeDirectionsByCovariance) {
  // Node 1 is measured twice from the fixed node 0: edge A says (1, 0, 0), edge B (0, 1, 0).
  // A is certain along x and uncertain along y; B the other way round: the optimum takes x
  // from A and y from B, i.e. near (1, 1, 0). With diagonal sigmas swapped it would be (0, 0).
  std::vector<Eigen::Isometry3d> poses = {Eigen::Isometry3d::Identity(),
                                          Eigen::Isometry3d::Identity()};
  PoseGraphEdge a, b;
  a.from = b.from = 0;
  a.to = b.to = 1;
  a.relative = pose_of(1, 0, 0, 0, 0, 0);
  b.relative = pose_of(0, 1, 0, 0, 0, 0);
  Matrix6d ca = Matrix6d::Identity() * 1e-6, cb = Matrix6d::Identity() * 1e-6;
  ca(1, 1) = 1e2;
  cb(0, 0) = 1e2;
  // A correlation that does not change the principal directions' meaning still has to be
  // positive definite: a small x-z term.
  ca(0, 2) = ca(2, 0) = 1e-7;
  a.covariance = ca;
  b.covariance = cb;
  ASSERT_TRUE(optimize_pose_graph(poses, {true, false}, {a, b}, {}).usable);
  EXPECT_NEAR(poses[1].translation().x(), 1.0, 1e-3);
  EXPECT_NEAR(poses[1].translation().y(), 1.0, 1e-3);
  EXPECT_NEAR(poses[1].translation().z(), 0.0, 1e-3);
}

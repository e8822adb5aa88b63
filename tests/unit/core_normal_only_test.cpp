// The normal-only ICP term (RegistrationConfig::normal_only_ratio, keep_normal_only): a
// plane-like combined precision keeps its normal alone; a line's is left whole; and a scan whose
// wall voxels are cut lower than the map's (as the top ring cuts a near wall lower than a far
// one) registers at its true pose only with it.

#include "litamin2/core/correspondence_search.hpp"
#include "litamin2/core/icp_term.hpp"
#include "litamin2/core/registration.hpp"
#include "litamin2/core/so3.hpp"
#include "litamin2/core/voxel_map.hpp"
#include "litamin2/core/voxelizer.hpp"
#include "support/walled_street.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>

namespace litamin2 {
namespace {

using testing::walled_street;

Eigen::Matrix3d oriented(const Eigen::Matrix3d& rotation, double a, double b, double c) {
  return rotation * Eigen::Vector3d(a, b, c).asDiagonal() * rotation.transpose();
}

TEST(NormalOnly, APlanesPrecisionKeepsItsNormalAndItsWeight) {
  std::mt19937 rng(5);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Matrix3d r = so3_exp(Eigen::Vector3d(n(rng), n(rng), n(rng)));
    const Eigen::Matrix3d q = so3_exp(Eigen::Vector3d(0.1 * n(rng), 0.1 * n(rng), 0.1 * n(rng)));
    // A map wall and a scan patch of it, both thin along the third axis of `r`.
    const Eigen::Matrix3d cq = oriented(r, 0.75, 0.5, 4e-4);
    const Eigen::Matrix3d cp = oriented(r * q, 0.6, 0.2, 2e-4);
    Eigen::Matrix3d precision = combined_precision(cq, cp, 1e-6);
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> exact(precision);
    const Eigen::Vector3d normal = exact.eigenvectors().col(2);
    const double strongest = exact.eigenvalues()(2);
    ASSERT_TRUE(keep_normal_only(precision, 1.0));
    // s n n^T: rank one, along the exact normal, with the exact weight.
    const Eigen::Matrix3d expected = strongest * normal * normal.transpose();
    EXPECT_LT((precision - expected).norm(), 1e-3 * strongest) << precision;
  }
}

TEST(NormalOnly, ALinesPrecisionIsLeftWhole) {
  // Two parallel ring arcs along x: two equally strong directions across the line.
  const Eigen::Matrix3d arc = Eigen::Vector3d(0.75, 4e-4, 4e-4).asDiagonal();
  Eigen::Matrix3d precision = combined_precision(arc, arc, 1e-6);
  const Eigen::Matrix3d before = precision;
  EXPECT_FALSE(keep_normal_only(precision, 1.0));
  EXPECT_EQ(precision, before);
}

TEST(NormalOnly, TheRatioDecidesWhatIsAPlane) {
  // Precision eigenvalues 1, 0.3, 0.3: the weaker two sum to 0.6 of the strongest.
  const Eigen::Matrix3d r = so3_exp(Eigen::Vector3d(0.3, -0.2, 0.5));
  Eigen::Matrix3d precision = oriented(r, 1.0, 0.3, 0.3);
  EXPECT_FALSE(keep_normal_only(precision, 0.5));
  EXPECT_TRUE(keep_normal_only(precision, 0.7));
  // Rank one along the normal (first axis of r), found to about (0.3 / 1)^3 here, with about
  // its weight 1.
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> kept(precision);
  EXPECT_NEAR(kept.eigenvalues()(0), 0.0, 1e-12);
  EXPECT_NEAR(kept.eigenvalues()(1), 0.0, 1e-12);
  EXPECT_NEAR(kept.eigenvalues()(2), 1.0, 0.01);
  EXPECT_GT(std::abs(kept.eigenvectors().col(2).dot(r.col(0))), 0.99);
}

TEST(NormalOnly, APlanesThicknessWeightIsHalfAtTau) {
  EXPECT_EQ(plane_thickness_weight(0.0, 0.1), 1.0);
  EXPECT_DOUBLE_EQ(plane_thickness_weight(0.01, 0.1), 0.5);  // t = tau
  EXPECT_DOUBLE_EQ(plane_thickness_weight(0.04, 0.1), 0.2);  // t = 2 tau
  EXPECT_LT(plane_thickness_weight(0.09, 0.1), plane_thickness_weight(0.04, 0.1));
  EXPECT_EQ(plane_thickness_weight(0.5, 0.0), 1.0);  // off
}

/// The pose the scan cut at 3.5 m ahead and 4 m behind registers at, against the whole street,
/// from `initial` (the true pose is the identity).
RegistrationResult register_cut_walls(
    double normal_only_ratio, double start_factor = 1.0,
    const Eigen::Isometry3d& initial = Eigen::Isometry3d::Identity()) {
  VoxelizerConfig voxels;
  voxels.min_range = 0.0;
  VoxelMap map(voxels, VoxelMapConfig{});
  map.insert(walled_street(4.5, 4.5, 1), Eigen::Isometry3d::Identity());
  const auto search = make_correspondence_search(CorrespondenceMethod::kKdTree, map);
  Voxelizer voxelizer(voxels);
  const std::vector<Distribution> source = voxelizer.voxelize(walled_street(3.5, 4.0, 2));
  RegistrationConfig config;
  config.mode = CostMode::kIcp;
  config.max_isotropy = 1.0;
  config.normal_only_ratio = normal_only_ratio;
  config.normal_only_start_factor = start_factor;
  return register_distributions(source, map, *search, initial, config);
}

TEST(NormalOnly, WallsCutLowerThanTheMapsDoNotTiltTheScan) {
  const RegistrationResult whole = register_cut_walls(0.0);
  const RegistrationResult normal_only = register_cut_walls(1.0);
  ASSERT_TRUE(whole.valid);
  ASSERT_TRUE(normal_only.valid);
  const auto error = [](const RegistrationResult& result) {
    return std::make_pair(result.pose.translation().norm(),
                          Eigen::AngleAxisd(result.pose.linear()).angle() * 180.0 / M_PI);
  };
  const auto [whole_m, whole_deg] = error(whole);
  const auto [normal_m, normal_deg] = error(normal_only);
  // With the whole precision the walls' lower means pull the scan down and tilt it (measured
  // 4.4 mm, 0.0044 deg).
  EXPECT_GT(whole_m, 2e-3);
  EXPECT_GT(whole_deg, 3e-3);
  // With the normal alone the planes agree at about the true pose (0.15 mm, 0.0015 deg: the
  // cut voxels' normals are estimated from fewer points).
  EXPECT_LT(normal_m, 5e-4);
  EXPECT_LT(normal_deg, 0.5 * whole_deg);
  std::printf("whole precision: %.4f m %.4f deg; normal only: %.5f m %.5f deg\n", whole_m,
              whole_deg, normal_m, normal_deg);
}

TEST(NormalOnly, StartedBeforeConvergenceTheRefinementEndsWhereItDidAfter) {
  // A start 1 cm and 0.03 deg off, within the re-grid tolerances (2 cm, 0.1 deg) with the
  // whole precision's optimum, where the refinement starts.
  Eigen::Isometry3d initial = Eigen::Isometry3d::Identity();
  initial.translate(Eigen::Vector3d(0.008, -0.005, 0.003));
  initial.rotate(Eigen::AngleAxisd(0.03 * M_PI / 180.0, Eigen::Vector3d::UnitZ()));
  const RegistrationResult after = register_cut_walls(1.0, 1.0, initial);
  const RegistrationResult before = register_cut_walls(1.0, 10.0, initial);
  ASSERT_TRUE(after.valid);
  ASSERT_TRUE(before.valid);
  // Fewer iterations: the whole precision's last, smallest steps are left out.
  EXPECT_LT(before.iterations, after.iterations);
  const Eigen::Isometry3d delta = after.pose.inverse() * before.pose;
  // Both at the true pose as the refinement after convergence is (0.15 mm; see above), and
  // within a tenth of that of each other.
  EXPECT_LT(before.pose.translation().norm(), 5e-4);
  EXPECT_LT(delta.translation().norm(), 5e-5);
  EXPECT_LT(Eigen::AngleAxisd(delta.linear()).angle() * 180.0 / M_PI, 1e-4);
  std::printf("iterations %d -> %d; apart %.2e m %.2e deg\n", after.iterations, before.iterations,
              delta.translation().norm(), Eigen::AngleAxisd(delta.linear()).angle() * 180 / M_PI);
}

}  // namespace
}  // namespace litamin2

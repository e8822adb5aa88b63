// The line gate (RegistrationConfig::line_gate): correspondences whose combined covariance of
// Eq. 3 is a line (two parallel ring arcs) are left out of the cost; planes and round
// distributions are kept; a scan with too few other correspondences is registered with all.

#include "litamin2/core/correspondence_search.hpp"
#include "litamin2/core/icp_term.hpp"
#include "litamin2/core/registration.hpp"
#include "litamin2/core/so3.hpp"
#include "litamin2/core/voxel_map.hpp"
#include "litamin2/core/voxelizer.hpp"

#include <gtest/gtest.h>

#include <random>

namespace litamin2 {
namespace {

Eigen::Matrix3d diagonal(double a, double b, double c) {
  return Eigen::Vector3d(a, b, c).asDiagonal();
}

TEST(LineGate, CombinedSpreadSeparatesLinesFromPlanesAndRoundShapes) {
  const double lambda = 1e-6;
  // Two parallel arcs along x (3 m long, 2 cm thick): a line.
  const Eigen::Matrix3d arc = diagonal(0.75, 4e-4, 4e-4);
  EXPECT_LT(combined_spread(arc, arc, lambda), 0.01);
  // Two equal arcs at an angle a: (1 - cos a) / (1 + cos a), 0.1 at 35 degrees.
  for (const double degrees : {20.0, 45.0}) {
    const double a = degrees * M_PI / 180.0;
    const Eigen::Matrix3d turned = Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).matrix();
    EXPECT_NEAR(combined_spread(arc, turned * arc * turned.transpose(), lambda),
                (1.0 - std::cos(a)) / (1.0 + std::cos(a)), 2e-3);
  }
  // An arc on a planar map voxel (several rings): a plane.
  EXPECT_GT(combined_spread(diagonal(0.75, 0.5, 4e-4), arc, lambda), 0.3);
  // Round clutter.
  EXPECT_GT(combined_spread(diagonal(0.5, 0.4, 0.3), arc, lambda), 0.3);
  // The isotropy of a line is 0 too: the isotropy gate cannot tell it from a plane.
  EXPECT_LT(combined_isotropy(arc, arc, lambda), 0.01);
}

TEST(LineGate, TheBoundedTestAgreesWithTheEigenvalues) {
  // combined_is_line decides most cases from the trace, the minors and the Frobenius norm: it
  // must agree with the eigenvalue ratio everywhere, including near the gate. Half the pairs
  // are two line-like arcs at a random angle, so that lines and planes near the gate both occur.
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> log_scale(-5.0, 0.5);
  std::normal_distribution<double> n(0.0, 1.0);
  auto random_covariance = [&](bool arc) {
    const Eigen::Matrix3d r = so3_exp(Eigen::Vector3d(n(rng), n(rng), n(rng)));
    const double thin = std::pow(10.0, log_scale(rng) - 3.0);
    const Eigen::Vector3d eigenvalues =
        arc ? Eigen::Vector3d(std::pow(10.0, log_scale(rng)), thin, thin)
            : Eigen::Vector3d(std::pow(10.0, log_scale(rng)), std::pow(10.0, log_scale(rng)),
                              std::pow(10.0, log_scale(rng)));
    return Eigen::Matrix3d(r * eigenvalues.asDiagonal() * r.transpose());
  };
  int lines = 0, others = 0;
  for (const double gate : {0.02, 0.1, 0.3}) {
    for (int i = 0; i < 20000; ++i) {
      const bool arcs = i % 2 == 0;
      const Eigen::Matrix3d cq = random_covariance(arcs);
      const Eigen::Matrix3d cp = random_covariance(arcs);
      const bool expected = combined_spread(cq, cp, 1e-6) < gate;
      ASSERT_EQ(combined_is_line(cq, cp, 1e-6, gate), expected)
          << "gate " << gate << ", spread " << combined_spread(cq, cp, 1e-6);
      (expected ? lines : others)++;
    }
  }
  EXPECT_GT(lines, 10000);
  EXPECT_GT(others, 10000);
}

/// Points along a straight arc in x at (y, z), plus, with `plane`, a patch z = 4.5 over x, y.
PointCloud scene(double y, bool plane, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.01);
  PointCloud cloud;
  for (int i = 0; i < 60; ++i) {
    const double x = 0.1 + 2.8 * i / 59.0;
    cloud.points.push_back(Eigen::Vector3d(x, y + noise(rng), 1.5 + noise(rng)).cast<float>());
  }
  if (plane) {
    for (int i = 0; i < 15; ++i) {
      for (int j = 0; j < 15; ++j) {
        cloud.points.push_back(
            Eigen::Vector3d(0.1 + 0.19 * i, 0.1 + 0.19 * j, 4.5 + noise(rng)).cast<float>());
      }
    }
  }
  return cloud;
}

struct Fixture {
  VoxelizerConfig voxels;
  VoxelMap map{voxels, VoxelMapConfig{}};
  std::unique_ptr<CorrespondenceSearch> search;
  std::vector<Distribution> source;

  explicit Fixture(bool plane) {
    voxels.min_range = 0.0;
    map = VoxelMap(voxels, VoxelMapConfig{});
    // The map's arc at y = 1.5, the scan's at y = 2.0 (its sensor moved 0.5 m across the arc).
    map.insert(scene(1.5, plane, 1), Eigen::Isometry3d::Identity());
    search = make_correspondence_search(CorrespondenceMethod::kKdTree, map);
    Voxelizer voxelizer(voxels);
    source = voxelizer.voxelize(scene(2.0, plane, 2));
  }
};

TEST(LineGate, LeavesParallelArcsOutAndKeepsPlanes) {
  const Fixture f(true);
  ASSERT_EQ(f.map.distributions().size(), 2u);
  ASSERT_EQ(f.source.size(), 2u);
  RegistrationConfig config;
  config.mode = CostMode::kIcp;
  config.max_isotropy = 1.0;
  const CostEvaluation all =
      evaluate_cost(f.source, f.map, *f.search, Eigen::Isometry3d::Identity(), config);
  EXPECT_EQ(all.matched, 2);
  EXPECT_EQ(all.correspondences, 2);
  config.line_gate = 0.1;
  const CostEvaluation gated =
      evaluate_cost(f.source, f.map, *f.search, Eigen::Isometry3d::Identity(), config);
  EXPECT_EQ(gated.matched, 2);
  EXPECT_EQ(gated.correspondences, 1);  // the plane
  // The arcs' 0.5 m offset across the line is what the gate removes from the cost.
  EXPECT_LT(gated.cost, 0.5 * all.cost);
}

/// 24 straight arcs, one per voxel, along x, y and z in turn, moved by `offset`.
PointCloud arcs(const Eigen::Vector3d& offset, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.01);
  PointCloud cloud;
  for (int k = 0; k < 24; ++k) {
    const Eigen::Vector3d origin(3.0 * (k % 4), 3.0 * ((k / 4) % 3), 3.0 * (k / 12));
    for (int i = 0; i < 40; ++i) {
      Eigen::Vector3d p = origin + Eigen::Vector3d(1.2, 1.5, 1.8);
      p(k % 3) = origin(k % 3) + 0.1 + 2.8 * i / 39.0;
      p += offset + Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
      cloud.points.push_back(p.cast<float>());
    }
  }
  return cloud;
}

TEST(LineGate, TooFewCorrespondencesLeftRegistersWithAll) {
  VoxelizerConfig voxels;
  voxels.min_range = 0.0;
  VoxelMap map(voxels, VoxelMapConfig{});
  map.insert(arcs(Eigen::Vector3d::Zero(), 1), Eigen::Isometry3d::Identity());
  const auto search = make_correspondence_search(CorrespondenceMethod::kKdTree, map);
  Voxelizer voxelizer(voxels);
  const std::vector<Distribution> source = voxelizer.voxelize(arcs({0.05, 0.05, 0.05}, 2));
  ASSERT_EQ(source.size(), 24u);
  RegistrationConfig config;
  config.mode = CostMode::kIcp;
  config.max_isotropy = 1.0;
  config.line_gate = 0.1;
  config.min_correspondences = 10;
  // Every pair is a line: the gate alone would leave none and fail the registration.
  EXPECT_EQ(
      evaluate_cost(source, map, *search, Eigen::Isometry3d::Identity(), config).correspondences,
      0);
  const RegistrationResult result =
      register_distributions(source, map, *search, Eigen::Isometry3d::Identity(), config);
  EXPECT_TRUE(result.valid);
  EXPECT_EQ(result.correspondences, 24);
}

}  // namespace
}  // namespace litamin2

// The isotropy gate kept only while what it keeps holds every direction of the pose
// (RegistrationConfig::isotropy_min_information): on a highway the road and the barriers are
// planes whose normals say nothing along the road, and the round voxels (shrubs) do.

#include "litamin2/core/information_share.hpp"
#include "litamin2/core/registration_config.hpp"
#include "support/register_clouds.hpp"
#include "support/synthetic_scene.hpp"

#include <gtest/gtest.h>

#include <random>

namespace litamin2 {
namespace {

TEST(InformationShare, IsTheLeastShareOverEveryDirection) {
  // A random positive definite whole, and a part that holds it all but a share s along one
  // direction u: part = whole - (1 - s) (whole u)(whole u)^T / (u^T whole u).
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  Matrix6d a;
  for (int i = 0; i < 36; ++i) a(i / 6, i % 6) = normal(rng);
  const Matrix6d whole = a * a.transpose() + Matrix6d::Identity();
  Vector6d u;
  for (int i = 0; i < 6; ++i) u(i) = normal(rng);
  const Vector6d wu = whole * u;
  for (const double share : {0.0, 0.05, 0.3, 0.9}) {
    const Matrix6d part = whole - (1.0 - share) * wu * wu.transpose() / u.dot(wu);
    EXPECT_NEAR(smallest_information_share(part, whole), share, 1e-9) << share;
    // Along u itself the ratio is the share; no direction gives less.
    EXPECT_NEAR(u.dot(part * u) / u.dot(whole * u), share, 1e-9);
    for (int k = 0; k < 100; ++k) {
      Vector6d v;
      for (int i = 0; i < 6; ++i) v(i) = normal(rng);
      EXPECT_GE(v.dot(part * v) / v.dot(whole * v), share - 1e-9);
    }
  }
  EXPECT_NEAR(smallest_information_share(whole, whole), 1.0, 1e-9);
  // Units do not matter: a rotation block in degrees instead of radians gives the same share.
  Matrix6d scale = Matrix6d::Identity();
  scale.topLeftCorner<3, 3>() *= 180.0 / M_PI;
  const Matrix6d part = whole - 0.7 * wu * wu.transpose() / u.dot(wu);
  EXPECT_NEAR(smallest_information_share(scale * part * scale, scale * whole * scale),
              smallest_information_share(part, whole), 1e-9);
  // A whole that is not positive definite, or not finite: no share.
  EXPECT_EQ(smallest_information_share(part, Matrix6d::Zero()), 0.0);
  Matrix6d bad = whole;
  bad(2, 3) = std::nan("");
  EXPECT_EQ(smallest_information_share(part, bad), 0.0);
}

/// A straight highway along x: the road (z = 0, |y| < 8), a 1 m barrier at each edge
/// (y = +-8), and a shrub (a 0.7 m ball of points) every `shrub_spacing` m beyond each barrier.
PointCloud highway(unsigned seed, double shrub_spacing = 9.0) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> along(-45.0, 45.0), across(-8.0, 8.0), up(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.01), shrub(0.0, 0.7);
  PointCloud cloud;
  const auto add = [&](double x, double y, double z) {
    cloud.points.emplace_back(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z));
  };
  for (int i = 0; i < 40000; ++i) add(along(rng), across(rng), noise(rng));
  for (const double side : {-8.0, 8.0})
    for (int i = 0; i < 12000; ++i) add(along(rng), side + noise(rng), up(rng));
  for (double x = -40.5; x <= 40.5; x += shrub_spacing)
    for (const double y : {-10.5, 10.5})
      for (int i = 0; i < 600; ++i) add(x + shrub(rng), y + shrub(rng), 1.5 + shrub(rng));
  return cloud;
}

TEST(IsotropyInformation, TheShrubsHoldTheHighwayAlongTheRoad) {
  const PointCloud map_scan = highway(1);
  // The scan is taken 0.6 m further along the road: in the map's frame its points are where
  // the map's are, seen from x = 0.6, so registered from the identity the pose is x = 0.6.
  const Eigen::Isometry3d truth(Eigen::Translation3d(0.6, 0.0, 0.0));
  PointCloud scan = highway(2);
  for (Eigen::Vector3f& p : scan.points) p = (truth.inverse() * p.cast<double>()).cast<float>();

  RegistrationConfig gated;  // the defaults: isotropy gate 0.05, always applied
  gated.isotropy_min_information = 0.0;
  RegistrationConfig informed = gated;
  informed.isotropy_min_information = 0.3;
  const auto error_along = [&](const RegistrationConfig& config) {
    const RegistrationResult r =
        testing::register_clouds(map_scan, scan, Eigen::Isometry3d::Identity(), config);
    EXPECT_TRUE(r.valid);
    return std::abs(r.pose.translation().x() - truth.translation().x());
  };
  const double gated_error = error_along(gated);
  const double informed_error = error_along(informed);
  std::printf("error along the road: gate always %.3f m, gate kept while informed %.3f m\n",
              gated_error, informed_error);
  EXPECT_LT(informed_error, 0.05);
  EXPECT_GT(gated_error, 2.0 * informed_error);
}

TEST(IsotropyInformation, TheTestStreetKeepsTheGate) {
  // The synthetic street (buildings, poles, trees, cars), registered from 3 cm off as a
  // tracker's prediction would start it: what the gate keeps holds every direction, so the
  // gate stays and the registration is the gated one, bit for bit.
  const PointCloud map_scan = testing::synthetic_scene(5);
  const Eigen::Isometry3d truth = testing::planar_pose(0.4, 0.1, 1.0);
  const PointCloud scan = testing::transformed(testing::synthetic_scene(6), truth.inverse());
  RegistrationConfig gated;
  RegistrationConfig informed = gated;
  informed.isotropy_min_information = 0.3;
  const Eigen::Isometry3d start = truth * testing::planar_pose(0.03, -0.02, 0.1);
  const RegistrationResult a = testing::register_clouds(map_scan, scan, start, gated);
  const RegistrationResult b = testing::register_clouds(map_scan, scan, start, informed);
  EXPECT_TRUE(a.pose.matrix() == b.pose.matrix());
  EXPECT_LT((b.pose.translation() - truth.translation()).norm(), 0.05);
}

}  // namespace
}  // namespace litamin2

// The isotropy gate kept only while what it keeps holds every direction of the pose
// (RegistrationConfig::isotropy_min_information): on a highway the road and the barriers are
// planes whose normals say nothing along the road, and the round voxels (shrubs) do.

#include "litamin2/core/registration_config.hpp"
#include "support/register_clouds.hpp"
#include "support/synthetic_scene.hpp"

#include <gtest/gtest.h>

#include <random>

namespace litamin2 {
namespace {

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

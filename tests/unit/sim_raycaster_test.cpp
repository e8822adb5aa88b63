// Ray casting against known scenes, determinism and sensor patterns of the simulator.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <set>

#include "litamin2/sim/builtin_trajectory.hpp"
#include "litamin2/sim/lidar_model.hpp"
#include "litamin2/sim/raycaster.hpp"
#include "litamin2/sim/world.hpp"

namespace sim = litamin2::sim;

namespace {

/// Straight drive along +x at z = 0 (sensor height above a flat road), 10 Hz, 1 m a frame,
/// from x = -100 m.
std::vector<Eigen::Isometry3d> straight_path(int frames) {
  std::vector<Eigen::Isometry3d> poses;
  for (int i = 0; i < frames; ++i) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(i - 100.0, 0, 0);
    poses.push_back(T);
  }
  return poses;
}

bool same_bytes(const litamin2::PointCloud& a, const litamin2::PointCloud& b) {
  return a.size() == b.size() && a.intensities.size() == b.intensities.size() &&
         std::memcmp(a.points.data(), b.points.data(), a.size() * sizeof(Eigen::Vector3f)) == 0 &&
         std::memcmp(a.intensities.data(), b.intensities.data(), a.size() * sizeof(float)) == 0;
}

}  // namespace

TEST(SimRaycaster, RayAgainstGroundPlaneMatchesHeightOverSine) {
  const auto path = straight_path(201);
  const sim::World world(path, 7, sim::WorldOptions::ground_only());
  sim::Raycaster rc(world);
  const Eigen::Vector3d origin = path[100].translation();
  rc.prepare(origin, 120.0);
  const double h = world.options().sensor_height;
  for (double el_deg : {-24.9, -15.0, -8.0, -3.0, -1.5}) {
    for (double az_deg : {0.0, 45.0, 130.0, 270.0}) {
      const double el = el_deg * M_PI / 180.0, az = az_deg * M_PI / 180.0;
      const Eigen::Vector3d dir(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az),
                                std::sin(el));
      const auto hit = rc.cast(origin, dir, 120.0);
      ASSERT_TRUE(hit.has_value()) << el_deg << " " << az_deg;
      EXPECT_NEAR(hit->range, h / std::sin(-el), 1e-3 * hit->range) << el_deg << " " << az_deg;
      EXPECT_GT(hit->normal.z(), 0.999);
      // Asphalt on the road, sidewalk or grass beyond it.
      const Eigen::Vector3d q = origin + hit->range * dir;
      if (std::abs(q.y()) < world.options().road_half_width - 0.5) {
        EXPECT_EQ(hit->material, sim::Material::kAsphalt) << q.transpose();
      } else if (std::abs(q.y()) > world.options().road_half_width + 1.5) {
        EXPECT_NE(hit->material, sim::Material::kAsphalt) << q.transpose();
      }
    }
  }
  // Upward rays see nothing in a ground-only world.
  EXPECT_FALSE(rc.cast(origin, Eigen::Vector3d(1, 0, 0.1), 120.0).has_value());
}

TEST(SimRaycaster, NoisyScanOfGroundPlaneLiesOnThePlaneWithinNoise) {
  const auto path = straight_path(201);
  const sim::World world(path, 7, sim::WorldOptions::ground_only());
  sim::Raycaster rc(world);
  sim::LidarModel model = sim::LidarModel::hdl64();
  const auto cloud = rc.scan(path[100], model, 3);
  ASSERT_GT(cloud.size(), 30000u);
  const double h = model.mount_height;
  double sum2 = 0.0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3f& p = cloud.points[i];
    // Range error along the ray: r - h / sin(elevation).
    const double r = p.norm();
    const double expected = h / (-p.z() / r);
    const double err = r - expected;
    ASSERT_LT(std::abs(err), 6.0 * model.range_noise_sigma) << "point " << i;
    sum2 += err * err;
    EXPECT_GE(cloud.intensities[i], 0.0f);
    EXPECT_LE(cloud.intensities[i], 1.0f);
  }
  const double rms = std::sqrt(sum2 / cloud.size());
  EXPECT_NEAR(rms, model.range_noise_sigma, 0.3 * model.range_noise_sigma);
  // Only beams pointing down return, and every return is beyond the ego vehicle.
  for (const auto& p : cloud.points) {
    ASSERT_LT(p.z(), 0.0f);
    ASSERT_GE(p.norm(), model.min_range);
  }
}

TEST(SimRaycaster, SameSeedSameBytesDifferentSeedDifferent) {
  const auto path = sim::builtin_trajectory("loop");
  const sim::World w1(path, 42), w2(path, 42), w3(path, 43);
  sim::Raycaster r1(w1), r2(w2), r3(w3);
  const auto model = sim::LidarModel::hdl64();
  const auto a = r1.scan(path[10], model, 5);
  const auto b = r2.scan(path[10], model, 5);
  EXPECT_TRUE(same_bytes(a, b));
  // Same world, other noise seed: different bytes.
  const auto c = r1.scan(path[10], model, 6);
  EXPECT_FALSE(same_bytes(a, c));
  // Other world seed: different geometry.
  const auto d = r3.scan(path[10], model, 5);
  EXPECT_FALSE(same_bytes(a, d));
  EXPECT_NE(w1.objects().size() + 1000 * w1.objects().front().center.x(),
            w3.objects().size() + 1000 * w3.objects().front().center.x());
}

TEST(SimRaycaster, ResultIndependentOfThreadingAndScenes) {
  const auto path = sim::builtin_trajectory("loop");
  const sim::World world(path, 9);
  sim::RaycasterOptions serial;
  serial.parallel = false;
  sim::RaycasterOptions inst;
  inst.instancing = true;
  sim::Raycaster a(world), b(world, serial), c(world, inst);
  const auto model = sim::LidarModel::vlp16();
  const auto pa = a.scan(path[50], model, 1);
  EXPECT_TRUE(same_bytes(pa, b.scan(path[50], model, 1)));
  // The instanced scene finds the same surfaces (float rounding may differ slightly).
  const auto pc = c.scan(path[50], model, 1);
  EXPECT_NEAR(static_cast<double>(pc.size()), static_cast<double>(pa.size()), 0.002 * pa.size());
}

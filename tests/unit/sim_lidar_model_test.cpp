// Sensor patterns: beam layouts of the presets and the scans they produce in a city scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "litamin2/sim/builtin_trajectory.hpp"
#include "litamin2/sim/lidar_model.hpp"
#include "litamin2/sim/raycaster.hpp"
#include "litamin2/sim/world.hpp"

namespace sim = litamin2::sim;

namespace {

/// Index of the beam whose elevation is nearest to the point's.
int ring_of(const Eigen::Vector3f& p, const sim::LidarModel& m) {
  const double el = std::atan2(p.z(), std::hypot(p.x(), p.y())) * 180.0 / M_PI;
  int best = 0;
  for (std::size_t b = 1; b < m.beams(); ++b) {
    if (std::abs(m.elevations_deg[b] - el) < std::abs(m.elevations_deg[best] - el)) {
      best = static_cast<int>(b);
    }
  }
  return best;
}

sim::WorldOptions city() {
  sim::WorldOptions o;
  o.district_weights = {1.0, 0.0, 0.0};
  return o;
}

}  // namespace

TEST(SimLidarModel, Hdl64Layout) {
  const auto m = sim::LidarModel::hdl64();
  ASSERT_EQ(m.beams(), 64u);
  const auto [lo, hi] = std::minmax_element(m.elevations_deg.begin(), m.elevations_deg.end());
  EXPECT_NEAR(*hi, 2.0, 1e-9);
  EXPECT_NEAR(*lo, -24.9, 1e-9);
  EXPECT_GE(m.azimuth_steps, 1800);
  EXPECT_LE(m.azimuth_steps, 2200);
  EXPECT_DOUBLE_EQ(m.max_range, 120.0);
  EXPECT_NEAR(m.mount_height, 1.73, 1e-9);
  EXPECT_NEAR(m.range_noise_sigma, 0.02, 1e-9);
  // Beams are distinct and sorted top to bottom.
  for (std::size_t b = 1; b < m.beams(); ++b) {
    EXPECT_LT(m.elevations_deg[b], m.elevations_deg[b - 1]);
  }
}

TEST(SimLidarModel, PresetsByName) {
  EXPECT_EQ(sim::LidarModel::from_name("vlp16")->beams(), 16u);
  EXPECT_EQ(sim::LidarModel::from_name("os128")->beams(), 128u);
  EXPECT_EQ(sim::LidarModel::from_name("hdl64")->beams(), 64u);
  EXPECT_FALSE(sim::LidarModel::from_name("hdl32").has_value());
  const auto v = sim::LidarModel::vlp16();
  EXPECT_NEAR(v.elevations_deg.front(), 15.0, 1e-9);
  EXPECT_NEAR(v.elevations_deg.back(), -15.0, 1e-9);
}

TEST(SimLidarModel, Hdl64CityScanHasKittiLikePointCountAndElevations) {
  const auto path = sim::builtin_trajectory("loop");
  const sim::World world(path, 3, city());
  sim::Raycaster rc(world);
  const auto m = sim::LidarModel::hdl64();
  for (std::size_t f : {0u, 120u}) {
    const auto cloud = rc.scan(path[f], m, f);
    EXPECT_GE(cloud.size(), 95000u) << "frame " << f;
    EXPECT_LE(cloud.size(), 131000u) << "frame " << f;
    ASSERT_EQ(cloud.intensities.size(), cloud.size());
    double el_min = 90, el_max = -90;
    for (const auto& p : cloud.points) {
      const double el = std::atan2(p.z(), std::hypot(p.x(), p.y())) * 180.0 / M_PI;
      el_min = std::min(el_min, el);
      el_max = std::max(el_max, el);
      ASSERT_LE(p.norm(), m.max_range + 0.2);
    }
    EXPECT_NEAR(el_min, -24.9, 0.3);
    EXPECT_LE(el_max, 2.3);
    EXPECT_GE(el_max, 1.0);  // the upper beams see buildings in a city
  }
}

TEST(SimLidarModel, Vlp16ScanHas16Rings) {
  const auto path = sim::builtin_trajectory("loop");
  const sim::World world(path, 3, city());
  sim::Raycaster rc(world);
  const auto m = sim::LidarModel::vlp16();
  const auto cloud = rc.scan(path[30], m, 1);
  std::map<int, int> rings;
  for (const auto& p : cloud.points) {
    const int r = ring_of(p, m);
    const double el = std::atan2(p.z(), std::hypot(p.x(), p.y())) * 180.0 / M_PI;
    ASSERT_NEAR(el, m.elevations_deg[r], 0.05);  // points lie on their beam's cone
    ++rings[r];
  }
  EXPECT_EQ(rings.size(), 16u);
  EXPECT_LE(cloud.size(), 16u * 1800u);
  EXPECT_GT(cloud.size(), 10000u);
}

// The ego vehicle's body: ray-box hits, validation, and self-hits that stay fixed in the sensor
// frame while the vehicle moves through the world.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "litamin2/sim/builtin_trajectory.hpp"
#include "litamin2/sim/ego_body.hpp"
#include "litamin2/sim/raycaster.hpp"
#include "litamin2/sim/world.hpp"

namespace sim = litamin2::sim;

namespace {

Eigen::Vector3d direction(double az_deg, double el_deg) {
  const double a = az_deg * M_PI / 180.0, e = el_deg * M_PI / 180.0;
  return Eigen::Vector3d(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e));
}

std::vector<Eigen::Vector3f> near_points(const litamin2::PointCloud& c, double r) {
  std::vector<Eigen::Vector3f> out;
  for (const auto& p : c.points) {
    if (p.norm() < r) out.push_back(p);
  }
  return out;
}

}  // namespace

TEST(SimEgoBody, RayHitsTheNearestFace) {
  sim::EgoBody body;
  body.boxes.push_back({Eigen::Vector3d(-2, -1, -0.5), Eigen::Vector3d(-1, 1, -0.2), 0.3f});
  body.boxes.push_back({Eigen::Vector3d(-3, -1, -0.5), Eigen::Vector3d(-2.5, 1, 0.5), 0.6f});
  body.validate();
  // Straight back and down 11.3 deg: meets the top face z = -0.2 at x = -1.0.
  const auto down = body.intersect(direction(180.0, -std::atan(0.2) * 180.0 / M_PI));
  ASSERT_TRUE(down.has_value());
  EXPECT_NEAR(down->range, std::hypot(1.0, 0.2), 1e-9);
  EXPECT_TRUE(down->normal.isApprox(Eigen::Vector3d::UnitX()));  // entered through x = -1
  // Horizontal back: passes over the first box, hits the second one's front face at x = -2.5.
  const auto level = body.intersect(direction(180.0, 0.0));
  ASSERT_TRUE(level.has_value());
  EXPECT_NEAR(level->range, 2.5, 1e-9);
  EXPECT_FLOAT_EQ(level->reflectivity, 0.6f);
  EXPECT_FALSE(body.intersect(direction(0.0, -10.0)).has_value());  // nothing ahead
}

TEST(SimEgoBody, ValidationRejectsBadBoxes) {
  sim::EgoBody body;
  body.boxes.push_back({Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 1, 1), 0.3f});
  EXPECT_THROW(body.validate(), std::invalid_argument);  // contains the sensor
  body.boxes[0] = {Eigen::Vector3d(-2, -1, -1), Eigen::Vector3d(-2, 1, -0.5), 0.3f};
  EXPECT_THROW(body.validate(), std::invalid_argument);  // empty along x
  body.boxes[0] = {Eigen::Vector3d(-2, -1, -1), Eigen::Vector3d(-1, 1, -0.5), 1.5f};
  EXPECT_THROW(body.validate(), std::invalid_argument);  // reflectivity
  body.boxes[0].reflectivity = 0.5f;
  EXPECT_NO_THROW(body.validate());
  EXPECT_NO_THROW(sim::EgoBody::roof_rack().validate());
  EXPECT_FALSE(sim::EgoBody::from_name("bumper").has_value());
}

// The roof rack's returns are the same points in the sensor frame wherever the vehicle is,
// behind the sensor at 1-2 m, as on the real drive; the world's points change.
TEST(SimEgoBody, SelfHitsStayFixedInTheSensorFrame) {
  const auto path = sim::builtin_trajectory("loop");
  const sim::World world(path, 9);
  sim::Raycaster rc(world);
  sim::LidarModel model = sim::LidarModel::vlp16();
  model.range_noise_sigma = 0.0;  // exact comparison
  sim::SensorRig rig;
  rig.body = sim::EgoBody::roof_rack();
  sim::SweepRequest a, b;
  a.start = a.end = path[40];
  b.start = b.end = path[200];
  const auto scan_a = rc.scan(a, model, rig, 5);
  const auto scan_b = rc.scan(b, model, rig, 6);
  const auto near_a = near_points(scan_a.cloud, 2.0), near_b = near_points(scan_b.cloud, 2.0);
  ASSERT_GT(near_a.size(), 700u);
  // Dropout differs with the seed; the points that are there coincide.
  std::size_t matched = 0;
  for (const auto& p : near_a) {
    for (const auto& q : near_b) {
      if ((p - q).norm() < 1e-5f) {
        ++matched;
        break;
      }
    }
    EXPECT_LT(p.x(), -0.9f);  // behind the sensor
    EXPECT_GT(p.x(), -1.9f);
    EXPECT_LT(p.z(), -0.1f);
  }
  EXPECT_GT(matched, near_a.size() * 9 / 10);
  // Without the body there are none (the VLP-16's minimum range is 1 m, the ground is farther).
  const auto bare = rc.scan(a, model, sim::SensorRig{}, 5);
  EXPECT_TRUE(near_points(bare.cloud, 2.0).empty());
}

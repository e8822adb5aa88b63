#pragma once
// A structured synthetic scene for registration tests: a bumpy ground, building blocks, poles
// and clutter, sampled uniformly at random on the surfaces (not in a LiDAR ring pattern).

#include "litamin2/core/point_cloud.hpp"

#include <Eigen/Geometry>
#include <random>

namespace litamin2::testing {

inline PointCloud synthetic_scene(unsigned seed, int points = 60000) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.02);
  struct Box {
    Eigen::Vector3d lo, hi;
  };
  // Fixed layout (independent of seed) so that two samplings share the same geometry.
  std::mt19937 layout(7);
  std::uniform_real_distribution<double> ul(0.0, 1.0);
  std::vector<Box> boxes;
  for (int i = 0; i < 14; ++i) {
    const double side = i % 2 ? 1.0 : -1.0;
    const double x = -45.0 + i * 7.0 + ul(layout) * 3.0;
    const double y = side * (9.0 + ul(layout) * 8.0);
    boxes.push_back({Eigen::Vector3d(x, y - 2.0 - 3.0 * ul(layout), 0.0),
                     Eigen::Vector3d(x + 3.0 + 3.0 * ul(layout), y + 2.0, 4.0 + 8.0 * ul(layout))});
  }
  std::vector<Eigen::Vector2d> poles;
  for (int i = 0; i < 20; ++i)
    poles.emplace_back(-40.0 + 80.0 * ul(layout), ul(layout) < 0.5 ? -6.0 : 6.0);

  PointCloud cloud;
  auto add = [&](const Eigen::Vector3d& p) {
    cloud.points.push_back((p + Eigen::Vector3d(noise(rng), noise(rng), noise(rng))).cast<float>());
  };
  auto ground_z = [](double x, double y) { return 0.15 * std::sin(0.2 * x) * std::cos(0.15 * y); };
  for (int i = 0; i < points / 2; ++i) {
    const double x = -50.0 + 100.0 * u(rng), y = -25.0 + 50.0 * u(rng);
    add(Eigen::Vector3d(x, y, ground_z(x, y) - 1.7));
  }
  for (int i = 0; i < points * 3 / 10; ++i) {
    const Box& b = boxes[i % boxes.size()];
    const Eigen::Vector3d e = b.hi - b.lo;
    const int face = static_cast<int>(u(rng) * 4);
    Eigen::Vector3d p(b.lo.x() + e.x() * u(rng), b.lo.y() + e.y() * u(rng),
                      b.lo.z() + e.z() * u(rng) - 1.7);
    if (face == 0) p.x() = b.lo.x();
    if (face == 1) p.x() = b.hi.x();
    if (face == 2) p.y() = b.lo.y();
    if (face == 3) p.y() = b.hi.y();
    add(p);
  }
  for (int i = 0; i < points / 10; ++i) {
    const Eigen::Vector2d& c = poles[i % poles.size()];
    const double a = 2 * M_PI * u(rng);
    add(Eigen::Vector3d(c.x() + 0.15 * std::cos(a), c.y() + 0.15 * std::sin(a),
                        -1.7 + 5.0 * u(rng)));
  }
  for (int i = 0; i < points / 10; ++i) {  // clutter: bushes as random blobs
    const Eigen::Vector2d& c = poles[(i * 7) % poles.size()];
    add(Eigen::Vector3d(c.x() + 2.0 + 1.5 * u(rng), c.y() + 1.5 * u(rng), -1.7 + 1.2 * u(rng)));
  }
  return cloud;
}

/// A pose on the ground plane: (x, y) in metres and a yaw in degrees.
inline Eigen::Isometry3d planar_pose(double x, double y, double yaw_deg) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() =
      Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  pose.translation() = Eigen::Vector3d(x, y, 0.0);
  return pose;
}

inline PointCloud transformed(const PointCloud& cloud, const Eigen::Isometry3d& pose) {
  PointCloud out = cloud;
  for (auto& p : out.points) p = (pose * p.cast<double>()).cast<float>();
  return out;
}

}  // namespace litamin2::testing

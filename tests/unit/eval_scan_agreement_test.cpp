// The agreement of two scans under a motion (eval/scan_agreement.hpp): small at the motion the
// scans were made with, large at a wrong one; the range and height filters; bad config.

#include "litamin2/eval/scan_agreement.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

namespace litamin2::eval {
namespace {

/// Points on three walls and a few posts of a fixed scene, seen from `pose` (sensor frame),
/// 2 cm noise; plus a flat ground 1.7 m below the sensor.
PointCloud scene_from(const Eigen::Isometry3d& pose, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.02);
  std::vector<Eigen::Vector3d> world;
  for (int i = 0; i < 6000; ++i) {
    const double s = u(rng), h = -1.7 + 4.0 * u(rng);
    switch (i % 4) {
      case 0:
        world.emplace_back(-20.0 + 40.0 * s, 8.0, h);
        break;  // wall left
      case 1:
        world.emplace_back(-20.0 + 40.0 * s, -9.0, h);
        break;  // wall right
      case 2:
        world.emplace_back(15.0, -9.0 + 17.0 * s, h);
        break;    // wall ahead
      default: {  // posts every 4 m
        const double x = -16.0 + 4.0 * std::floor(8.0 * s);
        const double a = 2.0 * M_PI * u(rng);
        world.emplace_back(x + 0.2 * std::cos(a), 5.0 + 0.2 * std::sin(a), h);
      }
    }
    world.emplace_back(-20.0 + 40.0 * u(rng), -9.0 + 17.0 * u(rng), -1.7);  // ground
  }
  PointCloud scan;
  const Eigen::Isometry3d to_sensor = pose.inverse();
  for (const Eigen::Vector3d& w : world) {
    const Eigen::Vector3d n(noise(rng), noise(rng), noise(rng));
    scan.points.push_back((to_sensor * w + n).cast<float>());
  }
  return scan;
}

Eigen::Isometry3d pose_at(double x, double yaw_deg) {
  Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
  p.linear() = Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()).matrix();
  p.translation() = Eigen::Vector3d(x, 0.3, 0.0);
  return p;
}

TEST(ScanAgreement, SmallAtTheTrueMotionLargeAtAWrongOne) {
  const Eigen::Isometry3d a = pose_at(0.0, 0.0), b = pose_at(2.0, 5.0);
  const PointCloud earlier = scene_from(a, 1), later = scene_from(b, 2);
  const ScanAgreementConfig config;
  const ScanAgreement truth = scan_agreement(earlier, later, a.inverse() * b, config);
  const ScanAgreement still = scan_agreement(earlier, later, Eigen::Isometry3d::Identity(), config);
  const ScanAgreement off = scan_agreement(earlier, later, a.inverse() * pose_at(3.0, 5.0), config);
  EXPECT_GT(truth.measured, 100);
  EXPECT_LT(truth.median_m, 0.25);
  EXPECT_GT(still.median_m, 3.0 * truth.median_m);
  EXPECT_GT(off.median_m, 3.0 * truth.median_m);
}

TEST(ScanAgreement, FiltersLeaveOutNearFarAndLowPoints) {
  PointCloud earlier, later;
  earlier.points = {Eigen::Vector3f(10, 0, 0), Eigen::Vector3f(1, 0, 0), Eigen::Vector3f(50, 0, 0),
                    Eigen::Vector3f(10, 0, -1.5)};
  later.points = earlier.points;
  ScanAgreementConfig config;
  config.stride = 1;
  const ScanAgreement r = scan_agreement(earlier, later, Eigen::Isometry3d::Identity(), config);
  EXPECT_EQ(r.measured, 1);  // only (10, 0, 0): 1 m is too near, 50 m too far, z -1.5 too low
  EXPECT_EQ(r.median_m, 0.0);
  const ScanAgreement none =
      scan_agreement(PointCloud{}, later, Eigen::Isometry3d::Identity(), config);
  EXPECT_EQ(none.measured, 0);
  EXPECT_TRUE(std::isnan(none.median_m));
}

TEST(ScanAgreement, InvalidConfigIsRejected) {
  const PointCloud scan = scene_from(pose_at(0.0, 0.0), 3);
  ScanAgreementConfig config;
  config.stride = 0;
  EXPECT_THROW(scan_agreement(scan, scan, Eigen::Isometry3d::Identity(), config),
               std::invalid_argument);
  config = ScanAgreementConfig{};
  config.min_range = 40.0;  // above max_range
  EXPECT_THROW(validate(config), std::invalid_argument);
  config = ScanAgreementConfig{};
  config.min_z = std::nan("");
  EXPECT_THROW(validate(config), std::invalid_argument);
}

}  // namespace
}  // namespace litamin2::eval

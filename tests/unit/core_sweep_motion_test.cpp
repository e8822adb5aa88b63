// The motion within a sweep estimated with the pose (core/sweep_motion.hpp): distributions'
// mean firing times, the 12-unknown registration recovering a wrong deskew twist (which a wrong
// sign or time weight in its system would not), the prior, and the config's validation.

#include "litamin2/core/config_error.hpp"
#include "litamin2/core/correspondence_search.hpp"
#include "litamin2/core/deskew.hpp"
#include "litamin2/core/scan_registration.hpp"
#include "litamin2/core/sweep_motion.hpp"
#include "litamin2/core/voxel_map.hpp"
#include "litamin2/core/voxelizer.hpp"
#include "support/synthetic_scene.hpp"
#include "support/twists.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace litamin2 {
namespace {

using testing::angle_deg;
using testing::twist;

TEST(SweepMotion, DistributionTimesAreTheMeanTimesOfTheirPoints) {
  // Two voxels of 3 m with 6 points each (times 0.01..0.06 and 0.05..0.10) and one with 2
  // points (below min_points 5: no distribution), in the voxeliser's order of first occupancy.
  PointCloud scan;
  std::vector<float> times;
  for (int i = 0; i < 6; ++i) {
    scan.points.emplace_back(10.5f + 0.1f * i, 1.5f, 0.5f);
    times.push_back(0.01f * (i + 1));
  }
  for (int i = 0; i < 2; ++i) {
    scan.points.emplace_back(-20.5f, 4.5f + 0.1f * i, 0.5f);
    times.push_back(0.09f);
  }
  for (int i = 0; i < 6; ++i) {
    scan.points.emplace_back(1.5f, 16.5f + 0.2f * i, 1.0f);
    times.push_back(0.05f + 0.01f * i);
  }
  Voxelizer voxelizer{VoxelizerConfig{}};
  const std::vector<Distribution> source = voxelizer.voxelize(scan);
  ASSERT_EQ(source.size(), 2u);
  const DistributionTimes t = distribution_times(scan, times, voxelizer);
  ASSERT_EQ(t.mean.size(), 2u);
  ASSERT_EQ(t.spread.size(), 2u);
  EXPECT_NEAR(t.mean[0], 0.035, 1e-6);
  EXPECT_NEAR(t.mean[1], 0.075, 1e-6);
  EXPECT_NEAR(t.spread[0], 0.01 * std::sqrt(35.0 / 12.0), 1e-6);  // of 1..6 hundredths
  EXPECT_NEAR(t.spread[1], 0.01 * std::sqrt(35.0 / 12.0), 1e-6);
  EXPECT_NEAR(source[0].mean.x(), 10.75, 1e-5);  // the order is the distributions'
}

/// A static scene seen by a sensor moving at `truth` within a clockwise sweep starting behind
/// it (times from the azimuth, as a spinning LiDAR fires), deskewed with `used`.
struct DeskewedSweep {
  PointCloud deskewed;
  std::vector<float> times;
};

DeskewedSweep sweep_deskewed_with(const Twist& truth, const Twist& used, unsigned seed) {
  DeskewedSweep out;
  PointCloud raw = testing::synthetic_scene(seed, 40000);
  times_from_azimuth(raw, AzimuthTiming{}, out.times);
  for (std::size_t i = 0; i < raw.size(); ++i)
    raw.points[i] =
        (motion_after(truth, out.times[i]).inverse() * raw.points[i].cast<double>()).cast<float>();
  deskew(raw, out.times, used, out.deskewed);
  return out;
}

class SweepMotionRegistration : public ::testing::Test {
 protected:
  SweepMotionRegistration()
      : map_(VoxelizerConfig{}, VoxelMapConfig{}), voxelizer_(VoxelizerConfig{}) {
    // The map: another sampling of the same scene, still, at the identity.
    map_.insert(testing::synthetic_scene(1, 60000), Eigen::Isometry3d::Identity());
    search_ = make_correspondence_search(registration_.correspondence, map_);
  }
  RegistrationConfig registration_;
  VoxelMap map_;
  Voxelizer voxelizer_;
  std::unique_ptr<CorrespondenceSearch> search_;
};

TEST_F(SweepMotionRegistration, RecoversTheTwistDeskewGotWrong) {
  // 20 m/s with a turn; deskewed with a twist off by 0.25 rad/s of yaw, 0.05 of roll and 2 m/s
  // forward (at 30 m the last points moved 0.75 m too little).
  const Twist truth = twist(0.0, 0.0, 0.3, 20.0, 0.0, 0.0);
  const Twist used = twist(-0.05, 0.0, 0.05, 18.0, 0.0, 0.0);
  const DeskewedSweep s = sweep_deskewed_with(truth, used, 2);
  const Eigen::Isometry3d identity = Eigen::Isometry3d::Identity();

  // The pose alone, from the scan deskewed wrong: off by the bend.
  const ScanRegistration plain =
      register_scan(s.deskewed, voxelizer_, map_, *search_, identity, registration_);
  ASSERT_TRUE(plain.result.valid);

  const std::vector<Distribution> source = voxelizer_.voxelize(s.deskewed, identity);
  const DistributionTimes times = distribution_times(s.deskewed, s.times, voxelizer_);
  SweepMotionConfig weak;  // a prior that hardly holds: the data decide
  weak.angular_sigma = 10.0;
  weak.linear_sigma = 100.0;
  weak.max_iterations = 30;
  const SweepMotionResult r =
      register_with_sweep_motion(source, times, map_, *search_, identity, registration_, weak);
  ASSERT_TRUE(r.valid);
  const Eigen::Vector3d angular_error = truth.angular - used.angular;
  const Eigen::Vector3d linear_error = truth.linear - used.linear;
  std::printf(
      "plain: %.3f m %.3f deg; with the twist: %.3f m %.3f deg, correction (%.3f %.3f "
      "%.3f) rad/s (%.2f %.2f %.2f) m/s, %d iterations\n",
      plain.result.pose.translation().norm(), angle_deg(plain.result.pose.linear()),
      r.pose.translation().norm(), angle_deg(r.pose.linear()), r.correction.angular.x(),
      r.correction.angular.y(), r.correction.angular.z(), r.correction.linear.x(),
      r.correction.linear.y(), r.correction.linear.z(), r.iterations);
  EXPECT_LT((r.correction.angular - angular_error).norm(), 0.2 * angular_error.norm());
  EXPECT_LT((r.correction.linear - linear_error).norm(), 0.2 * linear_error.norm());
  // Measured: 0.015 m / 0.064 deg against the pose alone's 0.175 m / 0.877 deg.
  EXPECT_LT(r.pose.translation().norm(), 0.03);
  EXPECT_LT(angle_deg(r.pose.linear()), 0.15);
  EXPECT_LT(r.pose.translation().norm(), 0.25 * plain.result.pose.translation().norm());
  EXPECT_LT(angle_deg(r.pose.linear()), 0.25 * angle_deg(plain.result.pose.linear()));
}

TEST_F(SweepMotionRegistration, ARightTwistStaysAndAStrongPriorHoldsAWrongOne) {
  const Twist truth = twist(0.0, 0.0, 0.3, 20.0, 0.0, 0.0);
  const Eigen::Isometry3d identity = Eigen::Isometry3d::Identity();
  {
    const DeskewedSweep s = sweep_deskewed_with(truth, truth, 3);
    const std::vector<Distribution> source = voxelizer_.voxelize(s.deskewed, identity);
    const DistributionTimes times = distribution_times(s.deskewed, s.times, voxelizer_);
    const SweepMotionResult r = register_with_sweep_motion(source, times, map_, *search_, identity,
                                                           registration_, SweepMotionConfig{});
    ASSERT_TRUE(r.valid);
    EXPECT_LT(r.correction.angular.norm(), 0.01);
    EXPECT_LT(r.correction.linear.norm(), 0.1);
    EXPECT_LT(r.pose.translation().norm(), 0.03);
  }
  {
    const Twist used = twist(0.0, 0.0, 0.05, 18.0, 0.0, 0.0);
    const DeskewedSweep s = sweep_deskewed_with(truth, used, 4);
    const std::vector<Distribution> source = voxelizer_.voxelize(s.deskewed, identity);
    const DistributionTimes times = distribution_times(s.deskewed, s.times, voxelizer_);
    SweepMotionConfig strong;
    strong.angular_sigma = 1e-6;
    strong.linear_sigma = 1e-5;
    const SweepMotionResult r =
        register_with_sweep_motion(source, times, map_, *search_, identity, registration_, strong);
    ASSERT_TRUE(r.valid);
    EXPECT_LT(r.correction.angular.norm(), 1e-4);
    EXPECT_LT(r.correction.linear.norm(), 1e-3);
  }
}

TEST_F(SweepMotionRegistration, MismatchedTimesAreNotRegistered) {
  const DeskewedSweep s = sweep_deskewed_with(Twist{}, Twist{}, 5);
  const std::vector<Distribution> source =
      voxelizer_.voxelize(s.deskewed, Eigen::Isometry3d::Identity());
  DistributionTimes too_few;
  too_few.mean.assign(source.size() / 2, 0.05);
  too_few.spread.assign(source.size() / 2, 0.0);
  const SweepMotionResult r =
      register_with_sweep_motion(source, too_few, map_, *search_, Eigen::Isometry3d::Identity(),
                                 registration_, SweepMotionConfig{});
  EXPECT_FALSE(r.valid);
  EXPECT_EQ(r.iterations, 0);
}

TEST(SweepMotion, ConfigIsValidated) {
  EXPECT_NO_THROW(validate(SweepMotionConfig{}));
  const auto rejected = [](SweepMotionConfig c, const std::string& key) {
    try {
      validate(c);
      ADD_FAILURE() << key << " accepted";
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("deskew.sweep_motion." + key), std::string::npos)
          << e.what();
    }
  };
  SweepMotionConfig c;
  c.angular_sigma = 0.0;
  rejected(c, "angular_sigma");
  c = SweepMotionConfig{};
  c.linear_sigma = std::nan("");
  rejected(c, "linear_sigma");
  c = SweepMotionConfig{};
  c.max_time_spread_s = -1.0;
  rejected(c, "max_time_spread_s");
  c = SweepMotionConfig{};
  c.max_iterations = 0;
  rejected(c, "max_iterations");
  c = SweepMotionConfig{};
  c.min_speed_mps = -1.0;
  rejected(c, "min_speed_mps");
  c.min_speed_mps = std::nan("");
  rejected(c, "min_speed_mps");
}

}  // namespace
}  // namespace litamin2

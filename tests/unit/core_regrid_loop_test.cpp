// The re-grid loop's rule (RegridLoop): it settles where the corrections shrink, stops instead of
// oscillating where they do not, and never exceeds max_regrids.

#include "litamin2/core/scan_registration.hpp"

#include <gtest/gtest.h>

namespace litamin2 {
namespace {

Eigen::Isometry3d along_x(double x) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation().x() = x;
  return pose;
}

RegistrationResult valid_at(double x) {
  RegistrationResult result;
  result.pose = along_x(x);
  result.valid = true;
  return result;
}

/// Runs the loop with a fake pass that maps the grid pose's x to `pass(x)`.
template <class Pass>
RegridLoop run(const RegistrationConfig& config, double start, Pass pass) {
  RegridLoop loop(config, along_x(start));
  while (loop.next(valid_at(pass(loop.grid_pose().translation().x())))) {
  }
  return loop;
}

/// The loop with the contraction rule on.
RegistrationConfig contracting() {
  RegistrationConfig config;  // tolerance 0.02 m
  config.regrid_contraction = 0.5;
  return config;
}

TEST(RegridLoop, SettlesWhereCorrectionsShrink) {
  const RegistrationConfig config = contracting();
  // Each pass halves the distance to x = 1 (a contracting fixed-point iteration).
  const RegridLoop loop = run(config, 0.0, [](double x) { return x + 0.5 * (1.0 - x) + 0.0; });
  EXPECT_FALSE(loop.stopped());
  EXPECT_LE(loop.passes(), config.max_regrids + 1);
  EXPECT_NEAR(loop.result().pose.translation().x(), 1.0, 0.05);
}

TEST(RegridLoop, StopsInsteadOfOscillating) {
  const RegistrationConfig config = contracting();
  // Each pass jumps to the other side: 0 -> 0.5 -> 0 -> 0.5 ... (what the real VLP-16 drive's
  // loop does, docs/accuracy.md "Sparse sensors").
  const RegridLoop loop = run(config, 0.0, [](double x) { return x < 0.25 ? 0.5 : 0.0; });
  EXPECT_TRUE(loop.stopped());
  EXPECT_EQ(loop.passes(), 3);  // two re-grids are always allowed, the third did not shrink
  // The kept result is the previous pass's, whose pose the last grid was cut at.
  EXPECT_EQ(loop.result().pose.translation().x(), loop.grid_pose().translation().x());
}

TEST(RegridLoop, OffByDefaultAndBoundedByMaxRegrids) {
  RegistrationConfig config;  // regrid_contraction 0: off
  config.max_regrids = 4;
  const RegridLoop loop = run(config, 0.0, [](double x) { return x < 0.25 ? 0.5 : 0.0; });
  EXPECT_FALSE(loop.stopped());
  EXPECT_EQ(loop.passes(), config.max_regrids + 1);
}

TEST(RegridLoop, EndsOnAnInvalidPassOrWithinTolerance) {
  RegistrationConfig config;
  RegridLoop loop(config, along_x(0.0));
  EXPECT_FALSE(loop.next(RegistrationResult{}));  // invalid
  EXPECT_EQ(loop.passes(), 1);
  RegridLoop settled(config, along_x(0.0));
  EXPECT_FALSE(settled.next(valid_at(0.01)));  // within the 0.02 m tolerance
  EXPECT_FALSE(settled.stopped());
}

}  // namespace
}  // namespace litamin2

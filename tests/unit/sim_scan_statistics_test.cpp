// The scan statistics used to compare simulated and real scans, on clouds of known shape.
#include <gtest/gtest.h>

#include <cmath>

#include "litamin2/sim/scan_statistics.hpp"

namespace sim = litamin2::sim;

namespace {

/// One ring of a 16-beam sensor at elevation `el_deg` over a flat ground 1.7 m below, every
/// 0.2 deg, within 100 m; a wall at x = wall_x (if > 0) stops the rays ahead.
void ring(litamin2::PointCloud& c, double el_deg, double wall_x = 0.0) {
  const double e = el_deg * M_PI / 180.0;
  for (int a = 0; a < 1800; ++a) {
    const double az = 2.0 * M_PI * a / 1800.0;
    Eigen::Vector3d d(std::cos(e) * std::cos(az), std::cos(e) * std::sin(az), std::sin(e));
    double t = e < 0 ? 1.7 / -d.z() : 1e9;
    if (wall_x > 0 && d.x() > 0) t = std::min(t, wall_x / d.x());
    if (t < 100.0) c.points.push_back((t * d).cast<float>());
  }
}

}  // namespace

TEST(SimScanStatistics, RingsRangesAndShapesOfAFlatGround) {
  std::vector<double> elevations;
  for (int i = 0; i < 16; ++i) elevations.push_back(15.0 - 2.0 * i);
  litamin2::PointCloud c;
  ring(c, -15.0);
  ring(c, -13.0);
  c.points.push_back(Eigen::Vector3f(-1.1f, 0.0f, -0.3f));  // a self-hit
  const auto s = sim::compute_scan_statistics(c, elevations);
  EXPECT_EQ(s.points, 3601u);
  EXPECT_EQ(s.near_2m, 1u);
  ASSERT_EQ(s.ring_points.size(), 16u);
  EXPECT_EQ(s.ring_points[15], 1801u);  // -15 deg is the last (lowest) ring; the self-hit too
  EXPECT_EQ(s.ring_points[14], 1800u);
  EXPECT_NEAR(s.azimuth_step_deg, 0.2, 1e-3);
  EXPECT_LT(s.lowest_ring_roughness, 1e-3);
  EXPECT_NEAR(s.ground_height, 1.7, 1e-3);
  EXPECT_NEAR(s.ground_pitch_deg, 0.0, 1e-3);
  EXPECT_NEAR(s.ground_residual, 0.0, 1e-3);
  // Every voxel holds pieces of one or two ground rings: lines and horizontal planes, none round.
  EXPECT_GT(s.linear_3m + s.planar_3m, 0.99);
  EXPECT_EQ(s.round_3m, 0.0);
  EXPECT_GT(s.single_ring_3m, 0.3);
  double share = 0.0;
  for (double h : s.range_histogram) share += h;
  EXPECT_NEAR(share, 1.0, 1e-9);
}

TEST(SimScanStatistics, MeanOfScans) {
  litamin2::PointCloud a, b;
  ring(a, -15.0);
  ring(b, -15.0, 3.0);  // a wall 3 m ahead cuts part of the ring shorter
  sim::ScanStatisticsMean mean;
  mean.add(sim::compute_scan_statistics(a));
  mean.add(sim::compute_scan_statistics(b));
  EXPECT_EQ(mean.count(), 2u);
  EXPECT_NEAR(mean.mean("points"), 1800.0, 1e-9);
  const double near5 = mean.mean("range 2-5 m share");
  EXPECT_GT(near5, 0.05);
  EXPECT_LT(near5, 0.5);
  EXPECT_EQ(mean.mean("no such row"), 0.0);
  EXPECT_EQ(mean.rows().front().first, "points");
}

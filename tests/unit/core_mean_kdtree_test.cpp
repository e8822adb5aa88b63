// MeanKdTree (the map means' kd-tree behind KdTreeSearch) against a linear scan: the same
// nearest point and distances for random and clustered points, with a limit and without,
// including tiny and empty trees and points sharing coordinates.

#include "litamin2/core/mean_kdtree.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace litamin2 {
namespace {

double squared_distance(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  double sum = 0.0;
  for (int i = 0; i < 3; ++i) sum += (a(i) - b(i)) * (a(i) - b(i));
  return sum;
}

/// The linear scan's two nearest (first index wins a tie).
void linear_two(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& q, int idx[2],
                double d2[2]) {
  idx[0] = idx[1] = -1;
  d2[0] = d2[1] = std::numeric_limits<double>::infinity();
  for (int i = 0; i < static_cast<int>(points.size()); ++i) {
    const double d = squared_distance(q, points[i]);
    if (d < d2[0]) {
      d2[1] = d2[0];
      idx[1] = idx[0];
      d2[0] = d;
      idx[0] = i;
    } else if (d < d2[1]) {
      d2[1] = d;
      idx[1] = i;
    }
  }
}

std::vector<Eigen::Vector3d> cloud(std::mt19937& rng, int n, bool clustered) {
  std::uniform_real_distribution<double> u(-60.0, 60.0);
  std::normal_distribution<double> blob(0.0, 0.5);
  std::vector<Eigen::Vector3d> points;
  Eigen::Vector3d centre(0, 0, 0);
  for (int i = 0; i < n; ++i) {
    if (!clustered || i % 20 == 0) centre = Eigen::Vector3d(u(rng), u(rng), u(rng) / 10.0);
    points.push_back(clustered ? Eigen::Vector3d(centre + Eigen::Vector3d(blob(rng), blob(rng), 0))
                               : Eigen::Vector3d(u(rng), u(rng), u(rng) / 10.0));
  }
  return points;
}

TEST(MeanKdTree, AgreesWithALinearScan) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-70.0, 70.0);
  for (const int n : {0, 1, 2, 3, 10, 11, 57, 2000}) {
    for (const bool clustered : {false, true}) {
      const std::vector<Eigen::Vector3d> points = cloud(rng, n, clustered);
      const MeanKdTree tree(points);
      ASSERT_EQ(tree.size(), points.size());
      for (int q = 0; q < 300; ++q) {
        // Queries near a point (as a registered source mean is) and anywhere.
        Eigen::Vector3d query(u(rng), u(rng), u(rng) / 10.0);
        if (n > 0 && q % 2 == 0) query = points[q % n] + Eigen::Vector3d(0.3, -0.2, 0.1) * (q % 7);
        int expected[2];
        double expected_d2[2];
        linear_two(points, query, expected, expected_d2);
        int got[2];
        double got_d2[2];
        tree.nearest_two(query, got, got_d2);
        ASSERT_EQ(got[0], expected[0]) << "n " << n;
        ASSERT_EQ(got[1], expected[1]) << "n " << n;
        if (n > 0) {
          EXPECT_EQ(got_d2[0], expected_d2[0]);
        }
        if (n > 1) {
          EXPECT_EQ(got_d2[1], expected_d2[1]);
        }
        for (const double limit : {1.0, 9.0, 1e4}) {
          double d2 = -1.0;
          const int index = tree.nearest(query, limit, d2);
          ASSERT_EQ(index, expected_d2[0] < limit ? expected[0] : -1) << "n " << n;
          if (index >= 0) {
            EXPECT_EQ(d2, expected_d2[0]);
          }
        }
      }
    }
  }
}

TEST(MeanKdTree, PointsSharingACoordinateAreAllFound) {
  // A grid: many points share each split value, so both sides of a split hold equal ones.
  std::vector<Eigen::Vector3d> points;
  for (int x = 0; x < 12; ++x)
    for (int y = 0; y < 12; ++y) points.emplace_back(3.0 * x, 3.0 * y, 0.0);
  const MeanKdTree tree(points);
  for (int i = 0; i < static_cast<int>(points.size()); ++i) {
    double d2 = -1.0;
    EXPECT_EQ(tree.nearest(points[i] + Eigen::Vector3d(0.1, 0.2, 0.0), 9.0, d2), i);
    int got[2];
    double got_d2[2];
    tree.nearest_two(points[i], got, got_d2);
    EXPECT_EQ(got[0], i);
    EXPECT_EQ(got_d2[0], 0.0);
    EXPECT_EQ(got_d2[1], 9.0);  // a grid neighbour 3 m away
  }
}

/// Every point's own query finds it (or a point equal to it) at distance zero, and a query
/// anywhere finds what the linear scan finds.
void expect_agrees_with_linear_scan(const std::vector<Eigen::Vector3d>& points) {
  const MeanKdTree tree(points);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < static_cast<int>(points.size()); ++i) {
    const Eigen::Vector3d query = points[i] + 0.01 * Eigen::Vector3d(u(rng), u(rng), u(rng));
    int expected[2], got[2];
    double expected_d2[2], got_d2[2];
    linear_two(points, query, expected, expected_d2);
    tree.nearest_two(query, got, got_d2);
    ASSERT_EQ(got_d2[0], expected_d2[0]) << "point " << i;
    ASSERT_EQ(got_d2[1], expected_d2[1]) << "point " << i;
    ASSERT_EQ(points[got[0]], points[expected[0]]) << "point " << i;
  }
}

TEST(MeanKdTree, EqualPointsMoreThanALeafHolds) {
  // No split can separate them: the build must stop at one leaf, and all are found.
  std::vector<Eigen::Vector3d> points(40, Eigen::Vector3d(1.0, 2.0, 3.0));
  points.emplace_back(5.0, 2.0, 3.0);
  expect_agrees_with_linear_scan(points);
}

TEST(MeanKdTree, LopsidedCloudsAreSplitAtTheirMedian) {
  // A dense blob with a few far points: the widest side's midpoint would cut off only the far
  // points, so the build falls back to the median (and keeps its depth bounded).
  std::mt19937 rng(3);
  std::normal_distribution<double> blob(0.0, 0.01);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 3000; ++i) points.emplace_back(blob(rng), blob(rng), blob(rng));
  for (int i = 0; i < 5; ++i) points.emplace_back(100.0 * (i + 1), 0.0, 0.0);
  expect_agrees_with_linear_scan(points);
  // Points at doubling distances: every midpoint split would peel off one point.
  std::vector<Eigen::Vector3d> doubling;
  for (int i = 0; i < 60; ++i) doubling.emplace_back(std::ldexp(1.0, i - 30), 0.0, 0.0);
  expect_agrees_with_linear_scan(doubling);
}

}  // namespace
}  // namespace litamin2

// Pose-graph optimisation: the residual's conventions (a wrong sign or frame moves the nodes
// the wrong way), a drifting loop corrected by one loop edge, a wrong loop edge held off by the
// robust loss.

#include "litamin2/mapping/pose_graph.hpp"

#include "support/poses.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace litamin2::mapping;

namespace {

using litamin2::testing::pose_of;

double rotation_error_deg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return Eigen::AngleAxisd(a.rotation().transpose() * b.rotation()).angle() * 180.0 / M_PI;
}

/// `laps` laps of a 40 m square, poses 1 m apart, each lap 0.2 m above the one before.
std::vector<Eigen::Isometry3d> square_laps(int laps) {
  const int lap = 40;
  std::vector<Eigen::Isometry3d> truth;
  for (int i = 0; i < laps * lap; ++i) {
    const int side = (i % lap) / 10, step = i % 10;
    Eigen::Isometry3d corner = pose_of(0, 0, 0.2 * (i / lap), 0, 0, 0);
    for (int s = 0; s < side; ++s) corner = corner * pose_of(10.0, 0, 0, 0, 0, M_PI / 2);
    truth.push_back(corner * pose_of(step, 0, 0, 0, 0, 0));
  }
  return truth;
}

/// Odometry edges along `truth` that go 1 cm too far and turn 0.3 degrees too little a step,
/// and the poses they chain from truth[0].
void drifting_odometry(const std::vector<Eigen::Isometry3d>& truth,
                       std::vector<PoseGraphEdge>& edges, std::vector<Eigen::Isometry3d>& poses) {
  poses = {truth[0]};
  for (std::size_t i = 1; i < truth.size(); ++i) {
    PoseGraphEdge e;
    e.from = static_cast<int>(i - 1);
    e.to = static_cast<int>(i);
    const Eigen::Isometry3d exact = truth[i - 1].inverse() * truth[i];
    e.relative = exact * pose_of(0.01, 0, 0, 0, 0, -0.003);
    e.sigma << 0.05, 0.05, 0.05, 0.005, 0.005, 0.005;
    edges.push_back(e);
    poses.push_back(poses.back() * e.relative);
  }
}

}  // namespace

TEST(MappingPoseGraph, OneEdgePlacesTheFreeNodeExactly) {
  const Eigen::Isometry3d fixed_pose = pose_of(1.0, -2.0, 0.5, 0.1, -0.2, 0.7);
  const Eigen::Isometry3d relative = pose_of(3.0, 1.0, -0.2, 0.05, 0.1, -0.4);
  std::vector<Eigen::Isometry3d> poses = {fixed_pose, Eigen::Isometry3d::Identity()};
  PoseGraphEdge edge;
  edge.from = 0;
  edge.to = 1;
  edge.relative = relative;
  const PoseGraphResult result = optimize_pose_graph(poses, {true, false}, {edge}, {});
  ASSERT_TRUE(result.usable);
  EXPECT_TRUE(poses[0].isApprox(fixed_pose, 1e-12));
  const Eigen::Isometry3d expected = fixed_pose * relative;
  EXPECT_LT((poses[1].translation() - expected.translation()).norm(), 1e-6);
  EXPECT_LT(rotation_error_deg(poses[1], expected), 1e-5);
}

TEST(MappingPoseGraph, LoopEdgeRemovesAccumulatedDrift) {
  // A square of 40 poses 1 m apart; the odometry turns 0.3 degrees too little per corner step.
  const int n = 40;
  const std::vector<Eigen::Isometry3d> truth = square_laps(1);
  std::vector<PoseGraphEdge> edges;
  std::vector<Eigen::Isometry3d> poses;
  drifting_odometry(truth, edges, poses);
  const double drift_before = (poses[n - 1].translation() - truth[n - 1].translation()).norm();
  PoseGraphEdge loop;
  loop.from = 0;
  loop.to = n - 1;
  loop.relative = truth[0].inverse() * truth[n - 1];
  loop.sigma << 0.01, 0.01, 0.01, 0.001, 0.001, 0.001;
  loop.robust = false;  // the mapper adds a new loop without the robust loss (mapper.cpp)
  edges.push_back(loop);
  std::vector<bool> fixed(n, false);
  fixed[0] = true;
  ASSERT_TRUE(optimize_pose_graph(poses, fixed, edges, {}).usable);
  const double drift_after = (poses[n - 1].translation() - truth[n - 1].translation()).norm();
  EXPECT_GT(drift_before, 0.5);
  EXPECT_LT(drift_after, 0.05 * drift_before);
  double worst = 0.0;
  for (int i = 0; i < n; ++i)
    worst = std::max(worst, (poses[i].translation() - truth[i].translation()).norm());
  EXPECT_LT(worst, 0.5);
}

TEST(MappingPoseGraph, ConjugateGradientsSolveAsTheFactorisationDoes) {
  // Three laps of a 40 m square, 1 m steps, the odometry turning 0.3 degrees too little a step;
  // every pose is tied by a loop to the same place one lap before (a graph whose loops tie
  // every part to others, as a fleet's on the same streets). Solved by the sparse Cholesky
  // factorisation and by conjugate gradients (PoseGraphConfig::iterative_min_free_poses).
  const int lap = 40, n = 3 * lap;
  const std::vector<Eigen::Isometry3d> truth = square_laps(3);
  std::vector<PoseGraphEdge> edges;
  std::vector<Eigen::Isometry3d> start;
  drifting_odometry(truth, edges, start);
  for (int i = lap; i < n; ++i) {
    PoseGraphEdge loop;
    loop.from = i - lap;
    loop.to = i;
    loop.relative = truth[i - lap].inverse() * truth[i];
    loop.sigma << 0.01, 0.01, 0.01, 0.001, 0.001, 0.001;
    edges.push_back(loop);
  }
  std::vector<bool> fixed(n, false);
  fixed[0] = true;
  PoseGraphConfig factorised;
  factorised.iterative_min_free_poses = 0;
  PoseGraphConfig iterative;
  iterative.iterative_min_free_poses = n - 1;  // exactly the free poses
  std::vector<Eigen::Isometry3d> a = start, b = start;
  const PoseGraphResult by_factor = optimize_pose_graph(a, fixed, edges, factorised);
  const PoseGraphResult by_gradients = optimize_pose_graph(b, fixed, edges, iterative);
  ASSERT_TRUE(by_factor.usable);
  ASSERT_TRUE(by_gradients.usable);
  EXPECT_FALSE(by_factor.iterative);
  EXPECT_TRUE(by_gradients.iterative);
  iterative.iterative_min_free_poses = n;  // one more than the free poses: the factorisation
  std::vector<Eigen::Isometry3d> c = start;
  EXPECT_FALSE(optimize_pose_graph(c, fixed, edges, iterative).iterative);
  double drift = 0.0, worst_a = 0.0, apart = 0.0;
  for (int i = 0; i < n; ++i) {
    drift = std::max(drift, (start[i].translation() - truth[i].translation()).norm());
    worst_a = std::max(worst_a, (a[i].translation() - truth[i].translation()).norm());
    apart = std::max(apart, (a[i].translation() - b[i].translation()).norm());
  }
  std::printf("drift %.3f m, factorised %.4f m from the truth, apart %.6f m\n", drift, worst_a,
              apart);
  EXPECT_GT(drift, 1.0);
  EXPECT_LT(worst_a, 0.1 * drift);
  EXPECT_LT(apart, 0.01) << "conjugate gradients end elsewhere than the factorisation";
}

TEST(MappingPoseGraph, RobustLossLimitsAWrongLoop) {
  // A straight chain with exact odometry and one wrong loop edge claiming 5 m of error.
  const int n = 20;
  std::vector<Eigen::Isometry3d> poses;
  std::vector<PoseGraphEdge> edges;
  for (int i = 0; i < n; ++i) poses.push_back(pose_of(i, 0, 0, 0, 0, 0));
  for (int i = 1; i < n; ++i) {
    PoseGraphEdge e;
    e.from = i - 1;
    e.to = i;
    e.relative = pose_of(1, 0, 0, 0, 0, 0);
    e.sigma << 0.01, 0.01, 0.01, 0.001, 0.001, 0.001;
    edges.push_back(e);
  }
  PoseGraphEdge wrong;
  wrong.from = 0;
  wrong.to = n - 1;
  wrong.relative = pose_of(n - 1 + 5.0, 0, 0, 0, 0, 0);
  wrong.sigma << 0.1, 0.1, 0.1, 0.01, 0.01, 0.01;
  wrong.robust = true;
  edges.push_back(wrong);
  std::vector<bool> fixed(n, false);
  fixed[0] = true;
  ASSERT_TRUE(optimize_pose_graph(poses, fixed, edges, {}).usable);
  // Without the robust loss the end would move by about 5 m * 0.1^-2 / (0.1^-2 + ...) ~ 1 m.
  EXPECT_LT(std::abs(poses[n - 1].translation().x() - (n - 1)), 0.2);
}

TEST(MappingPoseGraph, LevelPriorPullsTiltTowardsTheFirstNode) {
  // A chain whose odometry pitches up 0.5 degrees per step: without the prior the last node is
  // tilted by 9.5 degrees; a 1 degree level prior against 0.5 degree odometry sigmas keeps it
  // near level. Without any prior the residuals are zero and nothing moves.
  const int n = 20;
  std::vector<Eigen::Isometry3d> poses = {Eigen::Isometry3d::Identity()};
  std::vector<PoseGraphEdge> edges;
  for (int i = 1; i < n; ++i) {
    PoseGraphEdge e;
    e.from = i - 1;
    e.to = i;
    e.relative = pose_of(1.0, 0, 0, 0, 0.5 * M_PI / 180.0, 0);
    e.sigma << 0.01, 0.01, 0.01, 0.5 * M_PI / 180.0, 0.5 * M_PI / 180.0, 0.5 * M_PI / 180.0;
    edges.push_back(e);
    poses.push_back(poses.back() * e.relative);
  }
  std::vector<bool> fixed(n, false);
  fixed[0] = true;
  auto tilt_deg = [](const Eigen::Isometry3d& p) {
    return std::acos(
               std::clamp((p.rotation().transpose() * Eigen::Vector3d::UnitZ()).z(), -1.0, 1.0)) *
           180.0 / M_PI;
  };
  PoseGraphConfig config;
  std::vector<Eigen::Isometry3d> without = poses;
  ASSERT_TRUE(optimize_pose_graph(without, fixed, edges, config).usable);
  EXPECT_NEAR(tilt_deg(without[n - 1]), 9.5, 0.01);
  config.level_prior_sigma_deg = 1.0;
  std::vector<Eigen::Isometry3d> with = poses;
  ASSERT_TRUE(optimize_pose_graph(with, fixed, edges, config).usable);
  EXPECT_LT(tilt_deg(with[n - 1]), 3.0);
  EXPECT_LT(tilt_deg(with[n - 1]), tilt_deg(without[n - 1]) / 3.0);
}

TEST(MappingPoseGraph, WithinReachRefusesRunawayAndNonFinitePoses) {
  // A chain of three 10 m edges: no solution moves a node more than 30 m.
  std::vector<Eigen::Isometry3d> before(4, Eigen::Isometry3d::Identity());
  std::vector<PoseGraphEdge> edges;
  for (int i = 0; i < 3; ++i) {
    before[static_cast<std::size_t>(i + 1)] = pose_of(10.0 * (i + 1), 0, 0, 0, 0, 0);
    PoseGraphEdge e;
    e.from = i;
    e.to = i + 1;
    e.relative = pose_of(10.0, 0, 0, 0, 0, 0);
    edges.push_back(e);
  }
  std::vector<Eigen::Isometry3d> after = before;
  after[3] = pose_of(35.0, 20.0, 0, 0, 0, 0.3);  // moved 25 m: possible
  EXPECT_TRUE(within_reach(before, after, edges));
  after[3] = pose_of(1e6, 0, 0, 0, 0, 0);  // ran off
  EXPECT_FALSE(within_reach(before, after, edges));
  after[3] = before[3];
  after[2].translation().y() = std::nan("");
  EXPECT_FALSE(within_reach(before, after, edges));
  EXPECT_FALSE(within_reach(before, {before[0]}, edges));
}

TEST(MappingPoseGraph, AConvergedSolveIsWithinReach) {
  // The drift-correcting loop of LoopEdgeRemovesAccumulatedDrift's kind: a square of four
  // 10 m edges with a 20 % scale drift, closed by a loop edge.
  std::vector<Eigen::Isometry3d> poses;
  std::vector<PoseGraphEdge> edges;
  for (int i = 0; i < 5; ++i) poses.push_back(pose_of(12.0 * i, 0, 0, 0, 0, 0));
  for (int i = 0; i < 4; ++i) {
    PoseGraphEdge e;
    e.from = i;
    e.to = i + 1;
    e.relative = pose_of(12.0, 0, 0, 0, 0, 0);
    edges.push_back(e);
  }
  PoseGraphEdge loop;
  loop.from = 0;
  loop.to = 4;
  loop.relative = pose_of(40.0, 0, 0, 0, 0, 0);
  loop.robust = true;
  edges.push_back(loop);
  std::vector<bool> fixed(poses.size(), false);
  fixed[0] = true;
  const std::vector<Eigen::Isometry3d> before = poses;
  const PoseGraphResult r = optimize_pose_graph(poses, fixed, edges, PoseGraphConfig{});
  EXPECT_TRUE(r.usable);
  EXPECT_FALSE(r.diverged);
  EXPECT_LT(poses[4].translation().x(), before[4].translation().x());  // pulled in by the loop
  EXPECT_TRUE(within_reach(before, poses, edges));
}

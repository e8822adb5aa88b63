#include "litamin2/eval/rpe.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "litamin2/eval/relative_error.hpp"

namespace le = litamin2::eval;

namespace {

std::vector<Eigen::Isometry3d> line(int frames, double step) {
  std::vector<Eigen::Isometry3d> poses;
  for (int i = 0; i < frames; ++i) {
    Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
    p.translation() = Eigen::Vector3d(0.0, 0.0, step * i);
    poses.push_back(p);
  }
  return poses;
}

}  // namespace

TEST(EvalRpe, IdenticalIsExactlyZero) {
  auto gt = line(50, 1.0);
  for (std::size_t i = 0; i < gt.size(); ++i) {
    gt[i].linear() = Eigen::AngleAxisd(0.03 * i, Eigen::Vector3d::UnitY()).toRotationMatrix();
  }
  const le::RpeResult r = le::compute_rpe(gt, gt);
  EXPECT_EQ(r.pairs, 49u);
  EXPECT_EQ(r.translation_rmse, 0.0);
  EXPECT_EQ(r.rotation_rmse_deg, 0.0);
}

TEST(EvalRpe, KnownStepErrorGivesKnownRpe) {
  const auto gt = line(50, 1.0);
  const auto est = line(50, 1.1);  // 0.1 m too far per frame
  const le::RpeResult r1 = le::compute_rpe(gt, est, 1);
  EXPECT_NEAR(r1.translation_rmse, 0.1, 1e-12);
  EXPECT_NEAR(r1.translation_mean, 0.1, 1e-12);
  EXPECT_EQ(r1.rotation_rmse_deg, 0.0);
  const le::RpeResult r5 = le::compute_rpe(gt, est, 5);
  EXPECT_EQ(r5.pairs, 45u);
  EXPECT_NEAR(r5.translation_rmse, 0.5, 1e-12);

  const le::RelativeError e = le::relative_error(gt[0], gt[3], est[0], est[3]);
  EXPECT_NEAR(e.translation, 0.3, 1e-12);
  EXPECT_EQ(e.rotation, 0.0);
}

TEST(EvalRpe, DegenerateInputs) {
  const auto gt = line(3, 1.0);
  const le::RpeResult r = le::compute_rpe(gt, gt, 5);
  EXPECT_EQ(r.pairs, 0u);
  EXPECT_TRUE(std::isnan(r.translation_rmse));
  EXPECT_THROW(le::compute_rpe(gt, gt, 0), std::invalid_argument);
  EXPECT_THROW(le::compute_rpe(gt, line(2, 1.0)), std::invalid_argument);
}

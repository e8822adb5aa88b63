#include "litamin2/eval/ate.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "litamin2/eval/alignment.hpp"

namespace le = litamin2::eval;

namespace {

// Non-planar helix-like trajectory with varying orientation.
std::vector<Eigen::Isometry3d> helix(int frames) {
  std::vector<Eigen::Isometry3d> poses;
  for (int i = 0; i < frames; ++i) {
    const double s = 0.05 * i;
    Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
    p.linear() = (Eigen::AngleAxisd(s, Eigen::Vector3d::UnitY()) *
                  Eigen::AngleAxisd(0.1 * std::sin(s), Eigen::Vector3d::UnitX()))
                     .toRotationMatrix();
    p.translation() = Eigen::Vector3d(20.0 * std::cos(s), 0.3 * i, 15.0 * std::sin(s));
    poses.push_back(p);
  }
  return poses;
}

Eigen::Isometry3d known_transform() {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() =
      Eigen::AngleAxisd(0.9, Eigen::Vector3d(0.2, -1.0, 0.4).normalized()).toRotationMatrix();
  t.translation() = Eigen::Vector3d(12.0, -3.5, 40.0);
  return t;
}

}  // namespace

TEST(EvalAte, RigidlyTransformedEstimateHasZeroErrorAndAlignmentRecoversT) {
  const auto gt = helix(300);
  const Eigen::Isometry3d t = known_transform();
  std::vector<Eigen::Isometry3d> est;
  for (const auto& p : gt) est.push_back(t * p);

  const le::AteResult r = le::compute_ate(gt, est);
  EXPECT_EQ(r.poses, 300u);
  EXPECT_LT(r.translation_rmse, 1e-9);
  EXPECT_LT(r.translation_max, 1e-9);
  EXPECT_LT(r.rotation_rmse_deg, 1e-6);
  EXPECT_EQ(r.scale, 1.0);
  // alignment maps the estimate onto the ground truth, i.e. it is T^-1.
  EXPECT_TRUE(r.alignment.inverse().matrix().isApprox(t.matrix(), 1e-9));

  // Without alignment the same estimate is far off.
  const le::AteResult raw = le::compute_ate(gt, est, le::AteAlignment::kNone);
  EXPECT_GT(raw.translation_rmse, 10.0);
  EXPECT_TRUE(raw.alignment.matrix().isIdentity());
}

TEST(EvalAte, Sim3AlignmentRecoversScale) {
  const auto gt = helix(200);
  const Eigen::Isometry3d t = known_transform();
  std::vector<Eigen::Isometry3d> est;
  for (const auto& p : gt) {
    Eigen::Isometry3d q = t * p;
    q.translation() *= 0.8;
    est.push_back(q);
  }
  const le::AteResult sim3 = le::compute_ate(gt, est, le::AteAlignment::kSim3);
  EXPECT_NEAR(sim3.scale, 1.0 / 0.8, 1e-9);
  EXPECT_LT(sim3.translation_rmse, 1e-8);
  EXPECT_LT(sim3.rotation_rmse_deg, 1e-6);
  const le::AteResult se3 = le::compute_ate(gt, est, le::AteAlignment::kSE3);
  EXPECT_GT(se3.translation_rmse, 1.0);
}

TEST(EvalAte, ConstantOffsetOnHalfThePosesGivesAnalyticRmse) {
  // Each ground-truth position appears twice in a row; the estimate adds d to every even pose.
  // The optimal alignment shifts by -d/2 (rotation stays identity because the cross-covariance
  // is symmetric), leaving |d|/2 on every pose. Without alignment: |d| on half the poses.
  const auto base = helix(150);
  std::vector<Eigen::Isometry3d> gt;
  for (const auto& p : base) {
    gt.push_back(p);
    gt.push_back(p);
  }
  const Eigen::Vector3d d(0.3, -0.4, 1.2);  // |d| = 1.3
  auto est = gt;
  for (std::size_t i = 0; i < est.size(); i += 2) est[i].translation() += d;

  const le::AteResult r = le::compute_ate(gt, est);
  EXPECT_NEAR(r.translation_rmse, 0.65, 1e-9);
  EXPECT_NEAR(r.translation_mean, 0.65, 1e-9);
  EXPECT_NEAR(r.translation_median, 0.65, 1e-9);
  EXPECT_NEAR(r.translation_max, 0.65, 1e-9);
  EXPECT_LT(r.rotation_rmse_deg, 1e-7);
  EXPECT_TRUE(r.alignment.translation().isApprox(-0.5 * d, 1e-9));

  const le::AteResult raw = le::compute_ate(gt, est, le::AteAlignment::kNone);
  EXPECT_NEAR(raw.translation_rmse, 1.3 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(raw.translation_mean, 0.65, 1e-12);
  EXPECT_NEAR(raw.translation_median, 0.65, 1e-12);  // mean of the middle values 0 and 1.3
  EXPECT_NEAR(raw.translation_max, 1.3, 1e-12);
  EXPECT_EQ(raw.rotation_rmse_deg, 0.0);
}

TEST(EvalAte, RotationErrorOfConstantRotationOffsetWithoutAlignment) {
  const auto gt = helix(100);
  auto est = gt;
  const Eigen::Matrix3d offset =
      Eigen::AngleAxisd(2.0 * 3.14159265358979323846 / 180.0, Eigen::Vector3d::UnitZ())
          .toRotationMatrix();
  for (auto& p : est) p.linear() = p.linear() * offset;
  const le::AteResult r = le::compute_ate(gt, est, le::AteAlignment::kNone);
  EXPECT_NEAR(r.rotation_rmse_deg, 2.0, 1e-9);
  EXPECT_EQ(r.translation_rmse, 0.0);
}

TEST(EvalAte, UmeyamaReturnsProperRotationForPlanarPoints) {
  std::vector<Eigen::Vector3d> src;
  std::vector<Eigen::Vector3d> dst;
  const Eigen::Matrix3d rot = Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitY()).toRotationMatrix();
  for (int i = 0; i < 20; ++i) {
    const Eigen::Vector3d p(std::cos(0.3 * i) * i, 0.0, std::sin(0.3 * i) * i);
    src.push_back(p);
    dst.push_back(rot * p + Eigen::Vector3d(1, 2, 3));
  }
  const le::Similarity3 t = le::umeyama_alignment(src, dst);
  EXPECT_NEAR(t.rotation.determinant(), 1.0, 1e-12);
  EXPECT_TRUE(t.rotation.isApprox(rot, 1e-9));
  EXPECT_TRUE(t.translation.isApprox(Eigen::Vector3d(1, 2, 3), 1e-9));
  EXPECT_EQ(t.scale, 1.0);
}

TEST(EvalAte, InvalidInputsThrow) {
  const auto gt = helix(10);
  const auto est = helix(9);
  EXPECT_THROW(le::compute_ate(gt, est), std::invalid_argument);
  EXPECT_THROW(le::compute_ate({}, {}), std::invalid_argument);
  EXPECT_THROW(le::umeyama_alignment({}, {}), std::invalid_argument);
}

TEST(EvalAte, UmeyamaOfOnePointIsTheTranslationBetweenThem) {
  // No spread: no rotation or scale can be fitted; the points are moved onto each other.
  for (const bool with_scale : {false, true}) {
    const auto t = litamin2::eval::umeyama_alignment({Eigen::Vector3d(1, 2, 3)},
                                                     {Eigen::Vector3d(4, 4, 4)}, with_scale);
    EXPECT_DOUBLE_EQ(t.scale, 1.0);
    EXPECT_TRUE(t(Eigen::Vector3d(1, 2, 3)).isApprox(Eigen::Vector3d(4, 4, 4)));
  }
}

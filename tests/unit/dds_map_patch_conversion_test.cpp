// MapPatch <-> Keyframe: round trips both ways and rejection of bad patches.

#include "litamin2/dds/map_patch_conversion.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace litamin2;

namespace {

Keyframe sample_keyframe() {
  Keyframe kf;
  kf.key = {"fleet/car_1", 42};
  kf.stamp.nanoseconds = 1'700'000'000'123'456'789;
  kf.odom_pose.linear() =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(0.2, -0.3, 1.0).normalized()).toRotationMatrix();
  kf.odom_pose.translation() = Eigen::Vector3d(12.5, -3.25, 0.75);
  Matrix6d a = Matrix6d::Random();
  kf.covariance = a * a.transpose() * 1e-4 + Matrix6d::Identity() * 1e-6;
  kf.voxel_size = 1.5;
  for (int i = 0; i < 50; ++i) {
    Distribution d;
    // Float-representable values, so that the trip through floats is exact.
    d.mean = Eigen::Vector3d(i * 0.5, -i * 0.25, 0.125 * (i % 7));
    d.cov << 0.5, 0.0625, 0.03125, 0.0625, 0.25, 0.015625, 0.03125, 0.015625, 0.125;
    d.count = 3 + i;
    kf.distributions.push_back(d);
  }
  return kf;
}

}  // namespace

TEST(MapPatchConversion, KeyframeRoundTrip) {
  const Keyframe kf = sample_keyframe();
  const litamin2::msg::MapPatch msg = dds::to_map_patch(kf, "fleet/car_1/odom");
  EXPECT_EQ(msg.stream_id(), "fleet/car_1");
  EXPECT_EQ(msg.keyframe_id(), 42u);
  EXPECT_EQ(msg.stamp().sec(), 1'700'000'000);
  EXPECT_EQ(msg.stamp().nanosec(), 123'456'789u);
  EXPECT_EQ(msg.frame_id(), "fleet/car_1/odom");
  const dds::PatchConversion converted = dds::from_map_patch(msg);
  ASSERT_TRUE(converted.ok()) << converted.message;
  const Keyframe* back = &converted.keyframe;
  EXPECT_EQ(back->key, kf.key);
  EXPECT_EQ(back->stamp.nanoseconds, kf.stamp.nanoseconds);
  EXPECT_EQ(back->voxel_size, kf.voxel_size);
  EXPECT_EQ(back->odom_pose.translation(), kf.odom_pose.translation());
  EXPECT_LT((back->odom_pose.linear() - kf.odom_pose.linear()).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_LT((back->covariance - kf.covariance).cwiseAbs().maxCoeff(), 1e-15);
  ASSERT_EQ(back->distributions.size(), kf.distributions.size());
  for (std::size_t i = 0; i < kf.distributions.size(); ++i) {
    EXPECT_EQ(back->distributions[i].mean, kf.distributions[i].mean);
    EXPECT_EQ(back->distributions[i].cov, kf.distributions[i].cov);
    EXPECT_EQ(back->distributions[i].count, kf.distributions[i].count);
    EXPECT_EQ(back->distributions[i].shape_cov, kf.distributions[i].cov);
    EXPECT_LT((back->distributions[i].shape_cov_inv * kf.distributions[i].cov -
               Eigen::Matrix3d::Identity())
                  .cwiseAbs()
                  .maxCoeff(),
              1e-12);
  }
}

TEST(MapPatchConversion, MessageRoundTrip) {
  const litamin2::msg::MapPatch msg = dds::to_map_patch(sample_keyframe(), "odom");
  const dds::PatchConversion converted = dds::from_map_patch(msg);
  ASSERT_TRUE(converted.ok());
  const litamin2::msg::MapPatch again = dds::to_map_patch(converted.keyframe, "odom");
  EXPECT_EQ(again.distributions(), msg.distributions());
  EXPECT_EQ(again.stamp(), msg.stamp());
  EXPECT_EQ(again.pose().position(), msg.pose().position());
  EXPECT_NEAR(again.pose().orientation().w(), msg.pose().orientation().w(), 1e-15);
  EXPECT_NEAR(again.pose().orientation().x(), msg.pose().orientation().x(), 1e-15);
  for (std::size_t i = 0; i < 36; ++i)
    EXPECT_NEAR(again.covariance()[i], msg.covariance()[i], 1e-15);
}

TEST(MapPatchConversion, RejectsBadPatches) {
  const litamin2::msg::MapPatch good = dds::to_map_patch(sample_keyframe(), "odom");
  const float nan = std::numeric_limits<float>::quiet_NaN();
  auto rejected = [](const litamin2::msg::MapPatch& msg, dds::PatchError error,
                     const std::string& expected) {
    const dds::PatchConversion result = dds::from_map_patch(msg);
    EXPECT_EQ(result.error, error) << dds::to_string(result.error);
    EXPECT_FALSE(result.ok());
    EXPECT_NE(result.message.find(expected), std::string::npos) << result.message;
  };
  auto m = good;
  m.stream_id("1bad");
  rejected(m, dds::PatchError::kBadStreamId, "stream id '1bad'");
  m = good;
  m.pose().position().x(std::nan(""));
  rejected(m, dds::PatchError::kBadPose, "pose: position holds a non-finite value");
  m = good;
  m.covariance()[3] = std::numeric_limits<double>::infinity();
  rejected(m, dds::PatchError::kBadCovariance, "covariance holds a non-finite value");
  m = good;
  m.voxel_size(0.0f);
  rejected(m, dds::PatchError::kBadVoxelSize, "voxel size");
  m = good;
  m.distributions()[7].mean()[1] = nan;
  rejected(m, dds::PatchError::kBadDistribution, "distribution 7: mean holds a non-finite value");
  m = good;
  m.distributions()[3].cov()[5] = nan;
  rejected(m, dds::PatchError::kBadDistribution,
           "distribution 3: covariance holds a non-finite value");
  m = good;
  m.stamp().nanosec(1'000'000'000u);
  rejected(m, dds::PatchError::kBadStamp, "nanosec");
}

// Regressions of the fuzzing campaign of issue 14: patches that used to be accepted, repaired,
// or to poison the store.
class MapPatchFindings : public ::testing::Test {
 protected:
  void expect(const litamin2::msg::MapPatch& msg, dds::PatchError error, const std::string& text,
              const dds::PatchConversionOptions& options = {}) {
    const dds::PatchConversion result = dds::from_map_patch(msg, options);
    EXPECT_EQ(result.error, error) << dds::to_string(result.error) << ": " << result.message;
    EXPECT_NE(result.message.find(text), std::string::npos) << result.message;
    EXPECT_TRUE(result.keyframe.distributions.empty());
  }
  const litamin2::msg::MapPatch good = dds::to_map_patch(sample_keyframe(), "odom");
};

TEST_F(MapPatchFindings, HugeFiniteTranslationIsRejectedBeforeItMakesANanCovariance) {
  for (double t : {1e154, 1e200, 1e300, -1e8}) {
    auto m = good;
    m.pose().position().y(t);
    expect(m, dds::PatchError::kBadPose, "position holds");
  }
}

TEST_F(MapPatchFindings, ZeroAndUnnormalisedQuaternionsAreRejectedNotRepaired) {
  auto m = good;
  m.pose().orientation().x(0);
  m.pose().orientation().y(0);
  m.pose().orientation().z(0);
  m.pose().orientation().w(0);
  expect(m, dds::PatchError::kBadPose, "not a unit quaternion (norm 0)");
  m = good;
  m.pose().orientation().w(m.pose().orientation().w() * 2.0);
  expect(m, dds::PatchError::kBadPose, "not a unit quaternion");
  // Rounding of a unit quaternion (as floats or 7 digits give) is accepted.
  m = good;
  m.pose().orientation().w(m.pose().orientation().w() * (1.0 + 1e-7));
  EXPECT_TRUE(dds::from_map_patch(m).ok());
}

TEST_F(MapPatchFindings, NonPositiveDefiniteOrAsymmetricCovariancesAreRejected) {
  auto m = good;
  for (std::size_t i = 0; i < 36; ++i) m.covariance()[i] = i % 7 == 0 ? -1.0 : 0.0;
  expect(m, dds::PatchError::kBadCovariance, "not positive semi-definite");
  m = good;
  m.covariance()[1] += 1.0;  // (0, 1) but not (1, 0)
  expect(m, dds::PatchError::kBadCovariance, "not symmetric");
  m = good;
  m.covariance()[0] = 1e300;
  expect(m, dds::PatchError::kBadCovariance, "beyond");
}

TEST_F(MapPatchFindings, BadDistributionsAreRejected) {
  auto m = good;
  m.distributions()[4].count(0);
  expect(m, dds::PatchError::kBadDistribution, "distribution 4: point count is 0");
  m = good;
  m.distributions()[5].count(0x80000000u);  // was clamped to INT_MAX
  expect(m, dds::PatchError::kBadDistribution, "distribution 5: point count 2147483648");
  m = good;
  m.distributions()[6].cov({-1.0f, 0.0f, 0.0f, -1.0f, 0.0f, -1.0f});  // negative definite
  expect(m, dds::PatchError::kBadDistribution, "distribution 6: covariance is not positive");
  m = good;
  m.distributions()[8].mean()[0] = 3e38f;
  expect(m, dds::PatchError::kBadDistribution, "distribution 8: mean holds");
}

TEST_F(MapPatchFindings, AbsurdVoxelSizesAreRejected) {
  for (float v : {1e-30f, 0.01f, 51.0f, 3e38f, -1.0f, std::numeric_limits<float>::infinity(),
                  std::numeric_limits<float>::quiet_NaN()}) {
    auto m = good;
    m.voxel_size(v);
    expect(m, dds::PatchError::kBadVoxelSize, "is not in [0.05, 50] m");
  }
  for (float v : {0.05f, 50.0f}) {
    auto m = good;
    m.voxel_size(v);
    EXPECT_TRUE(dds::from_map_patch(m).ok()) << v;
  }
}

TEST_F(MapPatchFindings, TooManyDistributionsAreRejectedBeforeConversion) {
  dds::PatchConversionOptions options;
  options.max_distributions = 49;  // the sample has 50
  expect(good, dds::PatchError::kTooManyDistributions, "50 distributions > limit 49", options);
  options.max_distributions = 50;
  EXPECT_TRUE(dds::from_map_patch(good, options).ok());
  // The default bounds the 10-million-distribution patch of the finding.
  EXPECT_LT(dds::PatchConversionOptions().max_distributions, 10'000'000u);
}

TEST_F(MapPatchFindings, KeyframeIdsBeyondTheStoreAreRejected) {
  auto m = good;
  m.keyframe_id(std::uint64_t{1} << 63);
  expect(m, dds::PatchError::kBadKeyframeId, "beyond 2^63 - 1");
}

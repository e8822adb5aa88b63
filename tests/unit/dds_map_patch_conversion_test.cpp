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
  rejected(m, dds::PatchError::kNonFinitePose, "non-finite pose");
  m = good;
  m.covariance()[3] = std::numeric_limits<double>::infinity();
  rejected(m, dds::PatchError::kNonFiniteCovariance, "non-finite covariance");
  m = good;
  m.voxel_size(0.0f);
  rejected(m, dds::PatchError::kBadVoxelSize, "voxel size");
  m = good;
  m.distributions()[7].mean()[1] = nan;
  rejected(m, dds::PatchError::kNonFiniteDistribution, "distribution 7 has a non-finite mean");
  m = good;
  m.distributions()[3].cov()[5] = nan;
  rejected(m, dds::PatchError::kNonFiniteDistribution,
           "distribution 3 has a non-finite covariance");
  m = good;
  m.stamp().nanosec(1'000'000'000u);
  rejected(m, dds::PatchError::kBadStamp, "nanosec");
}

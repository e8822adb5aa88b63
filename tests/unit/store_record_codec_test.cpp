#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "litamin2/store/record_codec.hpp"

namespace {

using namespace litamin2;
using namespace litamin2::store;

TEST(StoreRecordCodec, DistributionLayoutIsLittleEndianFloat32MeanTriangleAndCount) {
  Distribution d;
  d.mean = Eigen::Vector3d(1.0, -2.0, 0.5);
  d.cov << 4, 1, 0.5,  //
      1, 5, 0.25,      //
      0.5, 0.25, 6;
  d.count = 0x01020304;
  const std::string bytes = encode_distributions({d});
  ASSERT_EQ(bytes.size(), kDistributionBytes);
  // 1.0f is 0x3F800000: little-endian bytes 00 00 80 3F.
  EXPECT_EQ(bytes.substr(0, 4), std::string("\x00\x00\x80\x3F", 4));
  // The triangle is xx, xy, xz, yy, yz, zz = 4, 1, 0.5, 5, 0.25, 6; 6.0f is 0x40C00000.
  EXPECT_EQ(bytes.substr(32, 4), std::string("\x00\x00\xC0\x40", 4));
  EXPECT_EQ(bytes.substr(36, 4), std::string("\x04\x03\x02\x01", 4));
}

TEST(StoreRecordCodec, DecodingRebuildsTheSymmetricCovarianceAndRegularisedShape) {
  Distribution d;
  d.mean = Eigen::Vector3d(0.25, 1.5, -3.0);
  d.cov << 0.04, 0.01, 0.0,  //
      0.01, 0.03, 0.002,     //
      0.0, 0.002, 0.0003;    // a thin voxel: the shape clamp raises the smallest eigenvalue
  d.count = 17;
  const std::string bytes = encode_distributions({d});
  const RegularizerConfig config;
  const std::vector<Distribution> out = decode_distributions(bytes.data(), bytes.size(), config);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].count, 17);
  EXPECT_TRUE(out[0].mean.isApprox(d.mean, 1e-7));
  EXPECT_TRUE(out[0].cov.isApprox(d.cov, 1e-6));
  Eigen::Matrix3d cov, shape, shape_inv;
  regularize_for_terms(config, d.cov.cast<float>().cast<double>(), cov, shape, shape_inv);
  EXPECT_TRUE(out[0].shape_cov.isApprox(shape, 1e-12));
  EXPECT_TRUE(out[0].shape_cov_inv.isApprox(shape_inv, 1e-12));
  // The clamp changed the shape, so the test would notice a missing regularisation.
  EXPECT_FALSE(out[0].shape_cov.isApprox(d.cov, 1e-3));
}

TEST(StoreRecordCodec, WrongSizesAndValuesAreRejected) {
  const std::string pose = encode_pose(Eigen::Isometry3d::Identity());
  EXPECT_THROW(decode_pose(pose.data(), pose.size() - 8), std::invalid_argument);
  std::string nan_pose = pose;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::memcpy(nan_pose.data(), &nan, sizeof(double));
  EXPECT_THROW(decode_pose(nan_pose.data(), nan_pose.size()), std::invalid_argument);
  const std::string m = encode_matrix6(Matrix6d::Identity());
  EXPECT_THROW(decode_matrix6(m.data(), m.size() + 1), std::invalid_argument);
  Distribution one;
  one.count = 1;
  const std::string d = encode_distributions(std::vector<Distribution>(2, one));
  EXPECT_THROW(decode_distributions(d.data(), d.size() - 1, {}), std::invalid_argument);
  Distribution negative;
  negative.count = -1;
  EXPECT_THROW(encode_distributions({negative}), std::invalid_argument);
}

TEST(StoreRecordCodec, PoseAndMatrixRoundTripExactly) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.rotate(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()));
  pose.translation() << 1.0 / 3.0, -2e5, 7.125;
  const std::string p = encode_pose(pose);
  EXPECT_EQ(decode_pose(p.data(), p.size()).matrix(), pose.matrix());
  const Matrix6d a = Matrix6d::Random();
  const Matrix6d info = a * a.transpose();
  const std::string m = encode_matrix6(info);
  EXPECT_EQ(decode_matrix6(m.data(), m.size()), info);
}

}  // namespace

namespace {

/// `bytes` with the float64 at index i replaced by `value`.
std::string with_f64(std::string bytes, int i, double value) {
  std::memcpy(bytes.data() + 8 * i, &value, sizeof(double));
  return bytes;
}

}  // namespace

// Regressions of issue 14: what the codec reads back (and writes) is a valid value or an error.
TEST(StoreRecordCodec, NonOrthonormalRotationsAndReflectionsAreRejected) {
  const std::string pose = encode_pose(Eigen::Isometry3d::Identity());
  EXPECT_TRUE(decode_pose(pose.data(), pose.size()).isApprox(Eigen::Isometry3d::Identity()));
  // Column-major: entry 0 is R(0, 0), entry 4 is R(1, 1).
  const std::string scaled = with_f64(pose, 0, 1.5);
  EXPECT_THROW(decode_pose(scaled.data(), scaled.size()), std::invalid_argument);
  const std::string reflection = with_f64(pose, 4, -1.0);
  try {
    decode_pose(reflection.data(), reflection.size());
    ADD_FAILURE() << "a reflection was accepted as a rotation";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("reflection"), std::string::npos) << e.what();
  }
  Eigen::Isometry3d sheared = Eigen::Isometry3d::Identity();
  sheared.linear()(0, 1) = 0.1;
  EXPECT_THROW(encode_pose(sheared), std::invalid_argument);
}

TEST(StoreRecordCodec, InvalidDistributionsAreRejectedBothWays) {
  Distribution d;
  d.mean = Eigen::Vector3d(1, 2, 3);
  d.cov = Eigen::Matrix3d::Identity();
  d.count = 3;
  const std::string good = encode_distributions({d});
  EXPECT_EQ(decode_distributions(good.data(), good.size(), {}).size(), 1u);
  auto expect_rejected = [](Distribution bad, const std::string& text) {
    try {
      encode_distributions({bad});
      ADD_FAILURE() << "encoded: " << text;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
  };
  Distribution zero = d;
  zero.count = 0;
  expect_rejected(zero, "point count 0");
  Distribution negative_definite = d;
  negative_definite.cov = -Eigen::Matrix3d::Identity();
  expect_rejected(negative_definite, "not positive semi-definite");
  Distribution far = d;
  far.mean.x() = 1e30;
  expect_rejected(far, "mean holds");
  // The same in stored bytes: count 0 at offset 36, a negative xx at offset 12.
  std::string bytes = good;
  std::memset(bytes.data() + 36, 0, 4);
  EXPECT_THROW(decode_distributions(bytes.data(), bytes.size(), {}), std::invalid_argument);
  bytes = good;
  const float minus_one = -1.0f;
  std::memcpy(bytes.data() + 12, &minus_one, 4);
  EXPECT_THROW(decode_distributions(bytes.data(), bytes.size(), {}), std::invalid_argument);
}

TEST(StoreRecordCodec, NanCovarianceOfAHugeTranslationNeverComesBack) {
  const std::string good = encode_matrix6(Matrix6d::Identity());
  const std::string nan = with_f64(good, 7, std::numeric_limits<double>::quiet_NaN());
  EXPECT_THROW(decode_matrix6(nan.data(), nan.size()), std::invalid_argument);
  Matrix6d bad = Matrix6d::Identity();
  bad(1, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(encode_matrix6(bad), std::invalid_argument);
  Eigen::Isometry3d far = Eigen::Isometry3d::Identity();
  far.translation().x() = 1e154;
  EXPECT_THROW(encode_pose(far), std::invalid_argument);
}

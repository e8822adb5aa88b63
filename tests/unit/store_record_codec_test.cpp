#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "litamin2/core/covariance_regularizer.hpp"
#include "litamin2/core/value_checks.hpp"
#include "litamin2/core/voxel_key.hpp"
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

namespace {

/// One stored distribution, byte by byte (record_codec.hpp's layout), bypassing the encoder's
/// checks: what a corrupt or foreign store row may hold.
std::string stored_distribution(const Eigen::Vector3f& mean, const Eigen::Matrix3f& cov,
                                std::uint32_t count) {
  const float values[9] = {mean.x(),  mean.y(),  mean.z(),  cov(0, 0), cov(0, 1),
                           cov(0, 2), cov(1, 1), cov(1, 2), cov(2, 2)};
  std::string out(kDistributionBytes, '\0');
  std::memcpy(out.data(), values, sizeof(values));  // little-endian host
  std::memcpy(out.data() + 36, &count, 4);
  return out;
}

}  // namespace

// The decoder judges a stored distribution on the closed-form eigenvalues its regularisation
// uses and goes through the full check only near the boundary: its verdicts and results must
// be those of the full check (value_checks.hpp) followed by regularize_for_terms.
TEST(StoreRecordCodec, DecodingKeepsTheFullChecksVerdictAndResult) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const RegularizerConfig config;
  int accepted = 0, rejected = 0;
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Matrix3d rotation =
        Eigen::Quaterniond(Eigen::Vector4d(unit(rng), unit(rng), unit(rng), unit(rng)).normalized())
            .toRotationMatrix();
    const double largest = std::pow(10.0, 3.0 * unit(rng));
    // Full rank, thin, rank one, zero, and negative smallest eigenvalues around the
    // tolerance (1e-6 of the largest): accepted and rejected ones on both sides of it.
    const double kinds[] = {0.3, 1e-3, 0.0, -0.2e-6, -0.7e-6, -2e-6, -1e-3};
    const double smallest = kinds[i % 7] * largest;
    const double middle = (i % 11 == 0) ? 0.0 : 0.5 * largest;
    const Eigen::Matrix3d cov =
        i % 97 == 0
            ? Eigen::Matrix3d::Zero()
            : Eigen::Matrix3d(rotation * Eigen::Vector3d(largest, middle, smallest).asDiagonal() *
                              rotation.transpose());
    const Eigen::Vector3f mean(static_cast<float>(100 * unit(rng)),
                               static_cast<float>(100 * unit(rng)), static_cast<float>(unit(rng)));
    const Eigen::Matrix3f stored = cov.cast<float>();
    const std::string bytes = stored_distribution(mean, stored, 5);
    const Eigen::Matrix3d raw = stored.cast<double>();
    const bool valid = !checks::covariance_error<3>(raw).has_value();
    if (!valid) {
      EXPECT_THROW(decode_distributions(bytes.data(), bytes.size(), config), std::invalid_argument)
          << raw;
      ++rejected;
      continue;
    }
    ++accepted;
    const std::vector<Distribution> out = decode_distributions(bytes.data(), bytes.size(), config);
    ASSERT_EQ(out.size(), 1u);
    Eigen::Matrix3d expected_cov, expected_shape, expected_shape_inv;
    regularize_for_terms(config, raw, expected_cov, expected_shape, expected_shape_inv);
    EXPECT_EQ(out[0].mean, mean.cast<double>());
    EXPECT_EQ(out[0].cov, expected_cov);  // bit for bit: the same decomposition
    EXPECT_EQ(out[0].shape_cov, expected_shape);
    EXPECT_EQ(out[0].shape_cov_inv, expected_shape_inv);
    EXPECT_EQ(out[0].count, 5);
  }
  // Both verdicts were exercised, near the boundary too.
  EXPECT_GT(accepted, 1000);
  EXPECT_GT(rejected, 500);
}

// The encoder's checks keep their verdicts: a covariance is refused exactly when the full check
// refuses it as given or as it would be stored (float).
TEST(StoreRecordCodec, EncodingKeepsTheFullChecksVerdict) {
  std::mt19937 rng(15);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int refused = 0;
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Matrix3d rotation =
        Eigen::Quaterniond(Eigen::Vector4d(unit(rng), unit(rng), unit(rng), unit(rng)).normalized())
            .toRotationMatrix();
    const double kinds[] = {1e-2, 0.0, -0.3e-6, -0.9e-6, -3e-6};
    Distribution d;
    d.mean = Eigen::Vector3d(10 * unit(rng), 10 * unit(rng), unit(rng));
    d.cov = rotation * Eigen::Vector3d(2.0, 1.0, 2.0 * kinds[i % 5]).asDiagonal() *
            rotation.transpose();
    d.count = 7;
    const Eigen::Matrix3d as_stored = d.cov.cast<float>().cast<double>();
    const bool valid =
        !checks::covariance_error<3>(d.cov) && !checks::covariance_error<3>(as_stored);
    if (valid) {
      EXPECT_NO_THROW(encode_distributions({d})) << d.cov;
    } else {
      ++refused;
      try {
        encode_distributions({d});
        ADD_FAILURE() << "encoded " << d.cov;
      } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("not positive semi-definite"), std::string::npos)
            << e.what();
      }
    }
  }
  EXPECT_GT(refused, 100);
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

namespace {

TEST(StoreRecordCodec, TileVoxelsRoundTripExactlyWithTheirCentreAsOrigin) {
  const double voxel_size = 2.0;
  mapping::MapTile::Voxel v;
  v.key = pack_voxel(VoxelIndex(3, -4, 1));
  v.moments.count = 12;
  v.moments.sum = Eigen::Vector3d(0.1, -0.25, 1.0 / 3.0);
  v.moments.sum_sq << 1.5, 0.01, -0.02, 2.25, 0.003, 0.125;
  const std::string bytes = encode_tile_voxels({v});
  ASSERT_EQ(bytes.size(), kTileVoxelBytes);
  const auto back = decode_tile_voxels(bytes.data(), bytes.size(), voxel_size);
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].key, v.key);
  EXPECT_EQ(back[0].moments.count, 12);
  EXPECT_TRUE(back[0].moments.sum == v.moments.sum);
  EXPECT_TRUE(back[0].moments.sum_sq == v.moments.sum_sq);
  // The centre of voxel (3, -4, 1) of edge 2 m.
  EXPECT_TRUE(back[0].moments.origin == Eigen::Vector3d(7.0, -7.0, 3.0));
}

TEST(StoreRecordCodec, BadTileVoxelsAreRejected) {
  mapping::MapTile::Voxel v;
  v.moments.count = 0;  // no points
  EXPECT_THROW(encode_tile_voxels({v}), std::invalid_argument);
  v.moments.count = 3;
  v.moments.sum.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(encode_tile_voxels({v}), std::invalid_argument);
  v.moments.sum.x() = 0.0;
  std::string bytes = encode_tile_voxels({v});
  EXPECT_THROW(decode_tile_voxels(bytes.data(), bytes.size() - 1, 1.0), std::invalid_argument);
  std::memset(&bytes[8], 0, 4);  // count 0
  EXPECT_THROW(decode_tile_voxels(bytes.data(), bytes.size(), 1.0), std::invalid_argument);
}

TEST(StoreRecordCodec, TileSummaryRoundTrips) {
  mapping::TileSummary s;
  s.min_bound = Eigen::Vector3f(-1.0f, -2.0f, -3.0f);
  s.max_bound = Eigen::Vector3f(4.0f, 5.0f, 6.0f);
  s.sample = {Eigen::Vector3f(0.5f, 0.25f, 0.125f), Eigen::Vector3f(1.0f, 2.0f, 3.0f)};
  const std::string bytes = encode_tile_summary(s);
  mapping::TileSummary back;
  decode_tile_summary(bytes.data(), bytes.size(), back);
  EXPECT_TRUE(back.min_bound == s.min_bound);
  EXPECT_TRUE(back.max_bound == s.max_bound);
  ASSERT_EQ(back.sample.size(), 2u);
  EXPECT_TRUE(back.sample[1] == s.sample[1]);
  EXPECT_THROW(decode_tile_summary(bytes.data(), bytes.size() - 4, back), std::invalid_argument);
}

}  // namespace

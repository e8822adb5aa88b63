/// PointCloud2 <-> PointCloud: round trips and every kind of bad input.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "litamin2/dds/pointcloud2_conversion.hpp"
#include "litamin2/dds/time_conversion.hpp"

namespace litamin2::dds {
namespace {

constexpr std::uint8_t kFloat32 = 7;
constexpr std::uint8_t kFloat64 = 8;
constexpr std::uint8_t kUint16 = 4;

PointCloud random_cloud(std::size_t n, bool intensity, unsigned seed = 1) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-80.0f, 80.0f);
  PointCloud cloud;
  for (std::size_t i = 0; i < n; ++i) {
    cloud.points.emplace_back(u(rng), u(rng), u(rng));
    if (intensity) cloud.intensities.push_back(std::fabs(u(rng)) / 80.0f);
  }
  return cloud;
}

sensor_msgs::msg::PointField field(const std::string& name, std::uint32_t offset,
                                   std::uint8_t datatype, std::uint32_t count = 1) {
  sensor_msgs::msg::PointField f;
  f.name(name);
  f.offset(offset);
  f.datatype(datatype);
  f.count(count);
  return f;
}

template <typename T>
void put(std::vector<std::uint8_t>& data, std::size_t at, T value, bool big_endian = false) {
  std::uint8_t bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if (big_endian) std::reverse(bytes, bytes + sizeof(T));
  std::memcpy(data.data() + at, bytes, sizeof(T));
}

/// A cloud with FLOAT64 z first, padding, FLOAT32 x and y, UINT16 intensity: point_step 32,
/// organised as height x width with 8 padding bytes at the end of each row.
sensor_msgs::msg::PointCloud2 odd_layout(const PointCloud& cloud, std::uint32_t height,
                                         bool big_endian) {
  const std::uint32_t width = static_cast<std::uint32_t>(cloud.size()) / height;
  sensor_msgs::msg::PointCloud2 msg;
  msg.height(height);
  msg.width(width);
  msg.point_step(32);
  msg.row_step(32 * width + 8);
  msg.is_bigendian(big_endian);
  msg.fields({field("z", 0, kFloat64), field("rgb", 8, kFloat32), field("x", 12, kFloat32),
              field("y", 20, kFloat32), field("intensity", 24, kUint16)});
  std::vector<std::uint8_t> data(msg.row_step() * height, 0xAB);
  for (std::uint32_t r = 0; r < height; ++r) {
    for (std::uint32_t c = 0; c < width; ++c) {
      const std::size_t i = r * width + c;
      const std::size_t at = r * msg.row_step() + c * 32;
      put<double>(data, at + 0, cloud.points[i].z(), big_endian);
      put<float>(data, at + 12, cloud.points[i].x(), big_endian);
      put<float>(data, at + 20, cloud.points[i].y(), big_endian);
      put<std::uint16_t>(data, at + 24, static_cast<std::uint16_t>(i), big_endian);
    }
  }
  msg.data(std::move(data));
  return msg;
}

TEST(DdsPointCloud2, RoundTripWithIntensity) {
  const PointCloud cloud = random_cloud(1000, true);
  const auto msg = to_pointcloud2(cloud, Stamp::from_seconds(12.5), "car1");
  EXPECT_EQ(msg.header().frame_id(), "car1");
  EXPECT_EQ(msg.header().stamp().sec(), 12);
  EXPECT_EQ(msg.header().stamp().nanosec(), 500000000u);
  EXPECT_EQ(msg.point_step(), 16u);
  EXPECT_EQ(msg.row_step(), 16000u);
  EXPECT_EQ(msg.height(), 1u);
  EXPECT_EQ(msg.width(), 1000u);
  EXPECT_EQ(msg.data().size(), 16000u);
  const CloudConversion result = from_pointcloud2(msg);
  ASSERT_TRUE(result.ok()) << result.message;
  ASSERT_EQ(result.cloud.size(), cloud.size());
  ASSERT_EQ(result.cloud.intensities.size(), cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    EXPECT_EQ(result.cloud.points[i], cloud.points[i]);  // bit-identical
    EXPECT_EQ(result.cloud.intensities[i], cloud.intensities[i]);
  }
  EXPECT_EQ(result.non_finite, 0u);
  EXPECT_EQ(result.total_points, 1000u);
}

TEST(DdsPointCloud2, RoundTripWithoutIntensityWritesZero) {
  const PointCloud cloud = random_cloud(10, false);
  const auto result = from_pointcloud2(to_pointcloud2(cloud, Stamp::from_seconds(0.0), "f"));
  ASSERT_TRUE(result.ok());
  ASSERT_EQ(result.cloud.intensities.size(), 10u);
  for (float i : result.cloud.intensities) EXPECT_EQ(i, 0.0f);
  CloudConversionOptions no_intensity;
  no_intensity.read_intensity = false;
  EXPECT_FALSE(from_pointcloud2(to_pointcloud2(cloud, Stamp::from_seconds(0.0), "f"), no_intensity)
                   .cloud.has_intensities());
}

TEST(DdsPointCloud2, ZeroPointsIsAnEmptyCloud) {
  const auto msg = to_pointcloud2(PointCloud{}, Stamp::from_seconds(1.0), "f");
  const auto result = from_pointcloud2(msg);
  ASSERT_TRUE(result.ok()) << result.message;
  EXPECT_TRUE(result.cloud.empty());
  // Also height 0, row_step 0 and no data.
  auto msg2 = msg;
  msg2.width(5);
  msg2.height(0);
  msg2.row_step(80);
  EXPECT_TRUE(from_pointcloud2(msg2).ok());
}

class DdsPointCloud2Layout : public ::testing::TestWithParam<bool> {};

TEST_P(DdsPointCloud2Layout, Float64AnyOffsetOrganisedPaddedRows) {
  const bool big_endian = GetParam();
  const PointCloud cloud = random_cloud(60, false, 7);
  const auto msg = odd_layout(cloud, 3, big_endian);
  const auto result = from_pointcloud2(msg);
  ASSERT_TRUE(result.ok()) << result.message;
  ASSERT_EQ(result.cloud.size(), 60u);
  ASSERT_EQ(result.cloud.intensities.size(), 60u);
  for (std::size_t i = 0; i < 60; ++i) {
    EXPECT_EQ(result.cloud.points[i].x(), cloud.points[i].x());
    EXPECT_EQ(result.cloud.points[i].y(), cloud.points[i].y());
    EXPECT_EQ(result.cloud.points[i].z(),
              static_cast<float>(static_cast<double>(cloud.points[i].z())));
    EXPECT_EQ(result.cloud.intensities[i], static_cast<float>(i));
  }
}

INSTANTIATE_TEST_SUITE_P(Endianness, DdsPointCloud2Layout, ::testing::Values(false, true));

TEST(DdsPointCloud2, BigEndianFlagSwapsBytes) {
  // The same bytes read with the opposite flag give byte-swapped (different) values.
  PointCloud cloud;
  cloud.points.emplace_back(1.0f, 2.0f, 3.0f);
  auto msg = odd_layout(cloud, 1, true);
  auto ok = from_pointcloud2(msg);
  ASSERT_TRUE(ok.ok());
  EXPECT_EQ(ok.cloud.points[0], Eigen::Vector3f(1.0f, 2.0f, 3.0f));
  msg.is_bigendian(false);
  auto swapped = from_pointcloud2(msg);
  ASSERT_TRUE(swapped.ok());
  EXPECT_NE(swapped.cloud.points.size() == 1 ? swapped.cloud.points[0] : Eigen::Vector3f::Zero(),
            Eigen::Vector3f(1.0f, 2.0f, 3.0f));
}

TEST(DdsPointCloud2, NonFinitePointsAreDroppedAndCounted) {
  PointCloud cloud = random_cloud(10, true);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  cloud.points[1].x() = nan;
  cloud.points[4].y() = inf;
  cloud.points[7].z() = -inf;
  cloud.intensities[1] = nan;  // a "no return" point: NaN intensity too, dropped with it
  const auto result = from_pointcloud2(to_pointcloud2(cloud, Stamp::from_seconds(0.0), "f"));
  ASSERT_TRUE(result.ok());
  EXPECT_EQ(result.non_finite, 3u);
  EXPECT_EQ(result.total_points, 10u);
  ASSERT_EQ(result.cloud.size(), 7u);
  EXPECT_EQ(result.cloud.points[0], cloud.points[0]);
  EXPECT_EQ(result.cloud.points[1], cloud.points[2]);
  EXPECT_EQ(result.cloud.intensities[1], cloud.intensities[2]);
  EXPECT_EQ(result.cloud.points[6], cloud.points[9]);
}

TEST(DdsPointCloud2, NonFiniteIntensityOfAFinitePointRejectsTheMessage) {
  // Regression (issue 14): it used to become 0. Invalid data is rejected, not repaired.
  for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                    -std::numeric_limits<float>::infinity()}) {
    PointCloud cloud = random_cloud(10, true);
    cloud.intensities[2] = bad;
    const auto msg = to_pointcloud2(cloud, Stamp::from_seconds(0.0), "f");
    const auto result = from_pointcloud2(msg);
    EXPECT_EQ(result.error, CloudError::kNonFiniteIntensity);
    EXPECT_NE(result.message.find("point 2"), std::string::npos) << result.message;
    EXPECT_TRUE(result.cloud.points.empty());
    EXPECT_STREQ(to_string(result.error), "non_finite_intensity");
    // The daemon does not read intensities: the same message is a valid scan there.
    CloudConversionOptions xyz_only;
    xyz_only.read_intensity = false;
    EXPECT_TRUE(from_pointcloud2(msg, xyz_only).ok());
  }
}

TEST(DdsPointCloud2, WithoutIntensityGivesTheSamePointsOnEveryLayout) {
  // read_intensity = false takes a faster loop for native float32 x, y, z: same points, same
  // non-finite count as the general loop, for packed and for organised, padded rows.
  PointCloud cloud = random_cloud(600, true, 7);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  for (std::size_t i = 0; i < cloud.size(); i += 37) cloud.points[i].x() = nan;
  for (std::size_t i = 5; i < cloud.size(); i += 53) cloud.points[i].y() = inf;
  for (std::size_t i = 9; i < cloud.size(); i += 71) cloud.points[i].z() = -inf;
  sensor_msgs::msg::PointCloud2 padded = to_pointcloud2(cloud, Stamp::from_seconds(0.0), "f");
  padded.height(3);
  padded.width(200);
  padded.row_step(200 * padded.point_step() + 12);
  std::vector<std::uint8_t> data(padded.row_step() * 3, 0xCD);
  for (std::uint32_t r = 0; r < 3; ++r) {
    std::memcpy(data.data() + r * padded.row_step(),
                padded.data().data() + r * 200 * padded.point_step(), 200 * padded.point_step());
  }
  padded.data(std::move(data));
  CloudConversionOptions xyz_only;
  xyz_only.read_intensity = false;
  for (const auto& msg :
       {to_pointcloud2(cloud, Stamp::from_seconds(0.0), "f"), padded, odd_layout(cloud, 4, true)}) {
    const CloudConversion general = from_pointcloud2(msg);
    const CloudConversion fast = from_pointcloud2(msg, xyz_only);
    ASSERT_TRUE(general.ok());
    ASSERT_TRUE(fast.ok());
    EXPECT_GT(fast.non_finite, 20u);
    EXPECT_EQ(fast.non_finite, general.non_finite);
    EXPECT_EQ(fast.total_points, general.total_points);
    EXPECT_TRUE(fast.cloud.intensities.empty());
    ASSERT_EQ(fast.cloud.points.size(), general.cloud.points.size());
    EXPECT_EQ(fast.cloud.points, general.cloud.points);
  }
}

TEST(DdsPointCloud2, Float64OutOfFloatRangeIsNonFinite) {
  PointCloud cloud;
  cloud.points.emplace_back(1.0f, 2.0f, 3.0f);
  cloud.points.emplace_back(4.0f, 5.0f, 6.0f);
  auto msg = odd_layout(cloud, 1, false);
  auto data = msg.data();
  put<double>(data, 32 + 0, 1e300);
  msg.data(data);
  const auto result = from_pointcloud2(msg);
  ASSERT_TRUE(result.ok());
  EXPECT_EQ(result.non_finite, 1u);
  EXPECT_EQ(result.cloud.size(), 1u);
}

sensor_msgs::msg::PointCloud2 good_msg(std::size_t n = 8) {
  return to_pointcloud2(random_cloud(n, true), Stamp::from_seconds(0.0), "f");
}

void expect_error(const sensor_msgs::msg::PointCloud2& msg, CloudError error,
                  const CloudConversionOptions& options = {}) {
  const CloudConversion result = from_pointcloud2(msg, options);
  EXPECT_EQ(result.error, error) << "got " << to_string(result.error) << ": " << result.message;
  EXPECT_FALSE(result.ok());
  EXPECT_FALSE(result.message.empty());
  EXPECT_TRUE(result.cloud.empty());
}

TEST(DdsPointCloud2, TruncatedData) {
  auto msg = good_msg();
  auto data = msg.data();
  data.pop_back();
  msg.data(data);
  expect_error(msg, CloudError::kDataSizeMismatch);
  msg.data({});
  expect_error(msg, CloudError::kDataSizeMismatch);
}

TEST(DdsPointCloud2, TrailingBytesAreRejected) {
  auto msg = good_msg();
  auto data = msg.data();
  data.push_back(0);
  msg.data(data);
  expect_error(msg, CloudError::kDataSizeMismatch);
}

TEST(DdsPointCloud2, WidthHeightInconsistentWithData) {
  auto msg = good_msg(8);
  msg.width(4);
  msg.height(2);  // row_step still 8 * 16: data would have to be 256 bytes
  expect_error(msg, CloudError::kDataSizeMismatch);
  msg.width(16);
  msg.height(1);  // row_step 128 < 16 * 16
  expect_error(msg, CloudError::kBadRowStep);
}

TEST(DdsPointCloud2, WrongPointStep) {
  auto msg = good_msg();
  msg.point_step(12);  // intensity at 12..16 no longer fits
  expect_error(msg, CloudError::kFieldOutOfBounds);
  msg.point_step(0);
  expect_error(msg, CloudError::kFieldOutOfBounds);
  auto xyz_only = good_msg();
  xyz_only.fields({field("x", 0, kFloat32), field("y", 4, kFloat32), field("z", 8, kFloat32)});
  xyz_only.point_step(20);  // row_step 128 < 8 * 20
  expect_error(xyz_only, CloudError::kBadRowStep);
}

TEST(DdsPointCloud2, ZeroPointStepWithPoints) {
  sensor_msgs::msg::PointCloud2 msg;
  msg.fields({field("x", 0, kFloat32, 0), field("y", 0, kFloat32), field("z", 0, kFloat32)});
  msg.width(3);
  msg.height(1);
  expect_error(msg, CloudError::kBadFieldType);  // count 0
  msg.fields({field("x", 0, kFloat32), field("y", 0, kFloat32), field("z", 0, kFloat32)});
  expect_error(msg, CloudError::kFieldOutOfBounds);  // 4 bytes > point_step 0
}

TEST(DdsPointCloud2, WrongRowStep) {
  auto msg = good_msg();
  msg.row_step(msg.row_step() - 1);
  expect_error(msg, CloudError::kBadRowStep);
  msg.row_step(msg.row_step() + 2);  // larger than width * point_step: data size mismatch
  expect_error(msg, CloudError::kDataSizeMismatch);
}

TEST(DdsPointCloud2, MissingFields) {
  for (const char* missing : {"x", "y", "z"}) {
    auto msg = good_msg();
    auto fields = msg.fields();
    fields.erase(std::remove_if(fields.begin(), fields.end(),
                                [&](const auto& f) { return f.name() == missing; }),
                 fields.end());
    msg.fields(fields);
    expect_error(msg, CloudError::kMissingField);
  }
  auto msg = good_msg();
  msg.fields({});
  expect_error(msg, CloudError::kMissingField);
  // Case matters: "X" is not "x".
  msg = good_msg();
  auto fields = msg.fields();
  fields[0].name("X");
  msg.fields(fields);
  expect_error(msg, CloudError::kMissingField);
}

TEST(DdsPointCloud2, MissingIntensityIsFine) {
  auto msg = good_msg();
  auto fields = msg.fields();
  fields.pop_back();
  msg.fields(fields);
  const auto result = from_pointcloud2(msg);
  ASSERT_TRUE(result.ok());
  EXPECT_FALSE(result.cloud.has_intensities());
}

TEST(DdsPointCloud2, DuplicateFields) {
  auto msg = good_msg();
  auto fields = msg.fields();
  fields.push_back(field("y", 0, kFloat32));
  msg.fields(fields);
  expect_error(msg, CloudError::kDuplicateField);
  msg = good_msg();
  fields = msg.fields();
  fields.push_back(field("intensity", 0, kFloat32));
  msg.fields(fields);
  expect_error(msg, CloudError::kDuplicateField);
  // Duplicates of fields the conversion does not read are ignored.
  msg = good_msg();
  fields = msg.fields();
  fields.push_back(field("ring", 12, kUint16));
  fields.push_back(field("ring", 12, kUint16));
  msg.fields(fields);
  EXPECT_TRUE(from_pointcloud2(msg).ok());
}

TEST(DdsPointCloud2, WrongDatatype) {
  for (std::uint8_t datatype : {0, 1, 2, 3, 4, 5, 6, 9, 255}) {
    auto msg = good_msg();
    auto fields = msg.fields();
    fields[2].datatype(datatype);
    msg.fields(fields);
    expect_error(msg, CloudError::kBadFieldType);
  }
  for (std::uint8_t datatype : {0, 9, 200}) {
    auto msg = good_msg();
    auto fields = msg.fields();
    fields[3].datatype(datatype);
    msg.fields(fields);
    expect_error(msg, CloudError::kBadFieldType);
  }
  // FLOAT64 x at offset 8 of a 16-byte point is fine size-wise only up to offset 8.
  auto msg = good_msg();
  auto fields = msg.fields();
  fields[0].datatype(kFloat64);
  fields[0].offset(12);
  msg.fields(fields);
  expect_error(msg, CloudError::kFieldOutOfBounds);
}

TEST(DdsPointCloud2, FieldOffsetBeyondPointStep) {
  auto msg = good_msg();
  auto fields = msg.fields();
  fields[1].offset(13);
  msg.fields(fields);
  expect_error(msg, CloudError::kFieldOutOfBounds);
  fields[1].offset(0xFFFFFFFFu);  // no overflow in offset + size
  msg.fields(fields);
  expect_error(msg, CloudError::kFieldOutOfBounds);
  fields[1].offset(4);
  fields[1].count(0x7FFFFFFFu);
  msg.fields(fields);
  expect_error(msg, CloudError::kFieldOutOfBounds);
}

TEST(DdsPointCloud2, TooManyPoints) {
  CloudConversionOptions options;
  options.max_points = 7;
  expect_error(good_msg(8), CloudError::kTooManyPoints, options);
  EXPECT_TRUE(from_pointcloud2(good_msg(7), options).ok());
  options.max_points = 0;  // no limit
  EXPECT_TRUE(from_pointcloud2(good_msg(8), options).ok());
  // Huge width*height with no data: rejected by the size check, no allocation.
  auto msg = good_msg(0);
  msg.width(100000);
  msg.height(100000);
  msg.row_step(1600000);
  expect_error(msg, CloudError::kDataSizeMismatch);
  msg.data(std::vector<std::uint8_t>(16));
  expect_error(msg, CloudError::kDataSizeMismatch);
}

TEST(DdsPointCloud2, TenMillionPointsRejectedByDefaultLimit) {
  auto msg = good_msg(0);
  msg.width(10'000'000);
  msg.row_step(160'000'000);
  msg.data(std::vector<std::uint8_t>(160'000'000));
  const auto result = from_pointcloud2(msg);
  EXPECT_EQ(result.error, CloudError::kTooManyPoints) << result.message;
}

TEST(DdsPointCloud2, OverflowingDimensionsDoNotCrash) {
  auto msg = good_msg(0);
  msg.width(0xFFFFFFFFu);
  msg.height(0xFFFFFFFFu);
  msg.point_step(0xFFFFFFFFu);
  msg.row_step(0xFFFFFFFFu);
  expect_error(msg, CloudError::kBadRowStep);
}

TEST(DdsPointCloud2, ReusesOutput) {
  CloudConversion out;
  EXPECT_EQ(from_pointcloud2(good_msg(8), {}, out), CloudError::kNone);
  EXPECT_EQ(out.cloud.size(), 8u);
  auto bad = good_msg(8);
  bad.fields({});
  EXPECT_EQ(from_pointcloud2(bad, {}, out), CloudError::kMissingField);
  EXPECT_TRUE(out.cloud.empty());
  EXPECT_EQ(from_pointcloud2(good_msg(3), {}, out), CloudError::kNone);
  EXPECT_EQ(out.cloud.size(), 3u);
  EXPECT_TRUE(out.message.empty());
}

TEST(DdsPointCloud2, ErrorNames) {
  EXPECT_STREQ(to_string(CloudError::kNone), "none");
  EXPECT_STREQ(to_string(CloudError::kDataSizeMismatch), "data_size_mismatch");
  EXPECT_STREQ(to_string(CloudError::kTooManyPoints), "too_many_points");
}

}  // namespace
}  // namespace litamin2::dds

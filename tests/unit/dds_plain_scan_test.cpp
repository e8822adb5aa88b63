/// PlainScan <-> PointCloud: the round trip the zero-copy input relies on (bit-identical
/// points and times) and every kind of bad sample.

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <memory>
#include <random>

#include "litamin2/dds/plain_scan_conversion.hpp"
#include "litamin2/dds/pointcloud2_conversion.hpp"

namespace litamin2::dds {
namespace {

PointCloud random_cloud(std::size_t n, bool with_times, unsigned seed = 1) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-80.0f, 80.0f);
  std::uniform_real_distribution<float> t(-0.05f, 0.05f);
  PointCloud cloud;
  for (std::size_t i = 0; i < n; ++i) {
    cloud.points.emplace_back(u(rng), u(rng), u(rng));
    if (with_times) cloud.times.push_back(t(rng));
  }
  return cloud;
}

// 2 MiB: never on the stack.
std::unique_ptr<litamin2_zero_copy::msg::PlainScan> make_scan(const PointCloud& cloud) {
  auto scan = std::make_unique<litamin2_zero_copy::msg::PlainScan>();
  to_plain_scan(cloud, Stamp::from_seconds(12.25), "velodyne", *scan);
  return scan;
}

TEST(PlainScan, SizeIsTheFixedLayout) {
  // stamp 8 + frame_id 64 + point_count 4 + has_times 4 + 131072 x 16 bytes.
  EXPECT_EQ(sizeof(litamin2_zero_copy::msg::PlainScan), 2'097'232u);
  EXPECT_EQ(sizeof(litamin2_zero_copy::msg::PlainPoint), 16u);
}

TEST(PlainScan, RoundTripIsBitIdenticalToThePointCloud2Path) {
  const PointCloud cloud = random_cloud(1000, true);
  const auto scan = make_scan(cloud);
  EXPECT_EQ(scan->point_count(), 1000u);
  EXPECT_EQ(scan->has_times(), 1u);
  EXPECT_STREQ(scan->frame_id().data(), "velodyne");
  CloudConversionOptions options;
  options.read_time = true;
  CloudConversion plain;
  ASSERT_EQ(from_plain_scan(*scan, options, plain), CloudError::kNone) << plain.message;
  const CloudConversion pc2 =
      from_pointcloud2(to_pointcloud2(cloud, Stamp::from_seconds(12.25), "velodyne"), options);
  ASSERT_TRUE(pc2.ok());
  ASSERT_EQ(plain.cloud.points.size(), pc2.cloud.points.size());
  ASSERT_EQ(plain.cloud.times.size(), pc2.cloud.times.size());
  EXPECT_EQ(std::memcmp(plain.cloud.points.data(), pc2.cloud.points.data(),
                        plain.cloud.points.size() * sizeof(Eigen::Vector3f)),
            0);
  EXPECT_EQ(std::memcmp(plain.cloud.times.data(), pc2.cloud.times.data(),
                        plain.cloud.times.size() * sizeof(float)),
            0);
  EXPECT_EQ(plain.time_field, "time");
  EXPECT_TRUE(plain.cloud.intensities.empty());
  EXPECT_EQ(plain.total_points, 1000u);
}

TEST(PlainScan, TimesIgnoredWithoutReadTimeOrWithoutHasTimes) {
  const auto scan = make_scan(random_cloud(10, true));
  CloudConversion out;
  ASSERT_EQ(from_plain_scan(*scan, {}, out), CloudError::kNone);
  EXPECT_TRUE(out.cloud.times.empty());
  EXPECT_EQ(out.cloud.points.size(), 10u);
  const auto no_times = make_scan(random_cloud(10, false));
  EXPECT_EQ(no_times->has_times(), 0u);
  CloudConversionOptions options;
  options.read_time = true;
  ASSERT_EQ(from_plain_scan(*no_times, options, out), CloudError::kNone);
  EXPECT_TRUE(out.cloud.times.empty());
  EXPECT_EQ(out.time_field, "");
}

TEST(PlainScan, NonFinitePointsAreDroppedAndCounted) {
  PointCloud cloud = random_cloud(5, false);
  const auto scan = make_scan(cloud);
  scan->points()[1].x(std::numeric_limits<float>::quiet_NaN());
  scan->points()[3].z(-std::numeric_limits<float>::infinity());
  CloudConversion out;
  ASSERT_EQ(from_plain_scan(*scan, {}, out), CloudError::kNone);
  EXPECT_EQ(out.non_finite, 2u);
  ASSERT_EQ(out.cloud.points.size(), 3u);
  EXPECT_EQ(out.cloud.points[0], cloud.points[0]);
  EXPECT_EQ(out.cloud.points[1], cloud.points[2]);
  EXPECT_EQ(out.cloud.points[2], cloud.points[4]);
}

TEST(PlainScan, EmptyScanIsValidAndEmpty) {
  const auto scan = make_scan(PointCloud());
  CloudConversion out;
  ASSERT_EQ(from_plain_scan(*scan, {}, out), CloudError::kNone);
  EXPECT_TRUE(out.cloud.empty());
}

TEST(PlainScan, BadSamplesAreRejectedWithAReason) {
  CloudConversionOptions options;
  options.read_time = true;
  CloudConversion out;
  auto check = [&](const litamin2_zero_copy::msg::PlainScan& scan, CloudError expected) {
    EXPECT_EQ(from_plain_scan(scan, options, out), expected) << out.message;
    EXPECT_FALSE(out.message.empty());
    EXPECT_TRUE(out.cloud.points.empty());
    EXPECT_TRUE(out.cloud.times.empty());
  };
  auto scan = make_scan(random_cloud(8, true));
  scan->point_count(static_cast<std::uint32_t>(kPlainScanCapacity) + 1);
  check(*scan, CloudError::kTooManyPoints);
  scan->point_count(0xFFFFFFFFu);
  check(*scan, CloudError::kTooManyPoints);
  scan->point_count(8);
  options.max_points = 7;
  check(*scan, CloudError::kTooManyPoints);
  options.max_points = 8;
  EXPECT_EQ(from_plain_scan(*scan, options, out), CloudError::kNone);

  scan->stamp().nanosec(1'000'000'000u);
  check(*scan, CloudError::kBadStamp);
  scan->stamp().nanosec(0);

  scan->frame_id().fill('a');
  check(*scan, CloudError::kBadFrameId);
  EXPECT_STREQ(to_string(CloudError::kBadFrameId), "bad_frame_id");
  scan->frame_id().fill('\0');

  scan->has_times(2);
  check(*scan, CloudError::kBadTimeField);
  scan->has_times(1);
  scan->points()[4].time(std::numeric_limits<float>::quiet_NaN());
  check(*scan, CloudError::kBadTimeField);
  scan->points()[4].time(1.5f);
  check(*scan, CloudError::kBadTimeField);
  // A bad time of a dropped (non-finite) point does not matter: the point is not kept.
  scan->points()[4].y(std::numeric_limits<float>::infinity());
  EXPECT_EQ(from_plain_scan(*scan, options, out), CloudError::kNone);
  EXPECT_EQ(out.non_finite, 1u);
  EXPECT_EQ(out.cloud.times.size(), 7u);
}

TEST(PlainScan, ToPlainScanRefusesWhatDoesNotFit) {
  auto scan = std::make_unique<litamin2_zero_copy::msg::PlainScan>();
  EXPECT_THROW(to_plain_scan(random_cloud(kPlainScanCapacity + 1, false), Stamp(), "f", *scan),
               std::invalid_argument);
  EXPECT_THROW(to_plain_scan(random_cloud(1, false), Stamp(), std::string(64, 'f'), *scan),
               std::invalid_argument);
  PointCloud bad_times = random_cloud(2, true);
  bad_times.times[1] = 2.0f;
  EXPECT_THROW(to_plain_scan(bad_times, Stamp(), "f", *scan), std::invalid_argument);
  EXPECT_NO_THROW(to_plain_scan(random_cloud(kPlainScanCapacity, false), Stamp(), "", *scan));
  EXPECT_EQ(scan->point_count(), kPlainScanCapacity);
}

}  // namespace
}  // namespace litamin2::dds

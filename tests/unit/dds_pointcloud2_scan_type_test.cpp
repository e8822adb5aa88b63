/// PointCloud2ScanType: a payload converted in place gives what the generated type's
/// deserialisation followed by from_pointcloud2 gives (points, counters, errors), and malformed
/// or oversized payloads are refused and recorded as CheckedType refuses them.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "litamin2/dds/checked_type.hpp"
#include "litamin2/dds/pointcloud2_conversion.hpp"
#include "litamin2/dds/pointcloud2_scan_type.hpp"
#include "sensor_msgs/msg/PointCloud2PubSubTypes.h"

namespace litamin2::dds {
namespace {

namespace rtps = eprosima::fastrtps::rtps;

PointCloud sample_cloud(std::size_t points, bool with_times) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-60.0f, 60.0f);
  PointCloud cloud;
  for (std::size_t i = 0; i < points; ++i) {
    cloud.points.emplace_back(u(rng), u(rng), u(rng));
    cloud.intensities.push_back(static_cast<float>(i % 256));
    if (with_times) cloud.times.push_back(0.09f * static_cast<float>(i) / points);
  }
  return cloud;
}

rtps::SerializedPayload_t serialized(sensor_msgs::msg::PointCloud2& msg) {
  sensor_msgs::msg::PointCloud2PubSubType generated;
  rtps::SerializedPayload_t payload(generated.getSerializedSizeProvider(&msg)());
  EXPECT_TRUE(generated.serialize(&msg, &payload));
  return payload;
}

/// What the daemon got before: the generated type (checked), then from_pointcloud2.
CloudConversion reference(rtps::SerializedPayload_t& payload, const CloudConversionOptions& o) {
  CheckedType<sensor_msgs::msg::PointCloud2PubSubType> checked;
  sensor_msgs::msg::PointCloud2 msg;
  EXPECT_TRUE(checked.deserialize(&payload, &msg));
  return from_pointcloud2(msg, o);
}

void expect_same(const CloudConversion& a, const CloudConversion& b) {
  EXPECT_EQ(a.error, b.error);
  EXPECT_EQ(a.message, b.message);
  EXPECT_EQ(a.cloud.points, b.cloud.points);
  EXPECT_EQ(a.cloud.intensities, b.cloud.intensities);
  EXPECT_EQ(a.cloud.times, b.cloud.times);
  EXPECT_EQ(a.non_finite, b.non_finite);
  EXPECT_EQ(a.total_points, b.total_points);
  EXPECT_EQ(a.time_field, b.time_field);
}

TEST(DdsPointCloud2ScanType, HasTheGeneratedTypesNameAndOnlyReads) {
  PointCloud2ScanType type;
  sensor_msgs::msg::PointCloud2PubSubType generated;
  EXPECT_STREQ(type.getName(), generated.getName());
  ReceivedPointCloud2 scan;
  rtps::SerializedPayload_t payload(64);
  EXPECT_FALSE(type.serialize(&scan, &payload));
}

TEST(DdsPointCloud2ScanType, ConvertsInPlaceAsTheGeneratedTypeAndConversionDo) {
  for (const bool with_times : {false, true}) {
    for (const bool read_intensity : {false, true}) {
      PointCloud cloud = sample_cloud(5000, with_times);
      // Non-finite points are dropped and counted on both paths.
      cloud.points[10].x() = std::numeric_limits<float>::quiet_NaN();
      cloud.points[20].z() = std::numeric_limits<float>::infinity();
      sensor_msgs::msg::PointCloud2 msg =
          to_pointcloud2(cloud, Stamp::from_seconds(1700000000.25), "velodyne");
      rtps::SerializedPayload_t payload = serialized(msg);
      CloudConversionOptions options;
      options.read_intensity = read_intensity;
      options.read_time = with_times;
      const CloudConversion expected = reference(payload, options);
      ASSERT_TRUE(expected.ok()) << expected.message;

      PointCloud2ScanType type;
      ReceivedPointCloud2 scan;
      scan.options = options;
      ASSERT_TRUE(type.deserialize(&payload, &scan));
      expect_same(scan.conversion, expected);
      EXPECT_EQ(scan.conversion.non_finite, 2u);
      EXPECT_EQ(scan.meta.header(), msg.header());
      EXPECT_EQ(scan.meta.fields(), msg.fields());
      EXPECT_EQ(scan.meta.width(), msg.width());
      EXPECT_EQ(scan.meta.row_step(), msg.row_step());
      EXPECT_EQ(scan.meta.is_dense(), msg.is_dense());
      EXPECT_TRUE(scan.meta.data().empty());
      EXPECT_EQ(payload.encapsulation, CDR_LE);
    }
  }
}

TEST(DdsPointCloud2ScanType, ReusedSampleGivesTheSameResult) {
  PointCloud2ScanType type;
  ReceivedPointCloud2 scan;
  for (const std::size_t n : {3000u, 100u, 3000u}) {
    sensor_msgs::msg::PointCloud2 msg = to_pointcloud2(sample_cloud(n, false), Stamp{}, "f");
    rtps::SerializedPayload_t payload = serialized(msg);
    ASSERT_TRUE(type.deserialize(&payload, &scan));
    expect_same(scan.conversion, reference(payload, scan.options));
  }
}

TEST(DdsPointCloud2ScanType, DeliversConversionErrorsAsTheConversionReportsThem) {
  sensor_msgs::msg::PointCloud2 msg = to_pointcloud2(sample_cloud(100, false), Stamp{}, "f");
  msg.row_step(msg.row_step() - 1);  // row_step < width * point_step
  rtps::SerializedPayload_t bad_step = serialized(msg);
  msg = to_pointcloud2(sample_cloud(100, false), Stamp{}, "f");
  msg.data().pop_back();  // data shorter than row_step * height
  rtps::SerializedPayload_t short_data = serialized(msg);
  msg = to_pointcloud2(sample_cloud(100, false), Stamp{}, "f");
  msg.fields().erase(msg.fields().begin() + 1);  // no y
  rtps::SerializedPayload_t no_y = serialized(msg);
  for (auto* payload : {&bad_step, &short_data, &no_y}) {
    PointCloud2ScanType type;
    ReceivedPointCloud2 scan;
    ASSERT_TRUE(type.deserialize(payload, &scan));
    EXPECT_FALSE(scan.conversion.ok());
    expect_same(scan.conversion, reference(*payload, scan.options));
    EXPECT_TRUE(scan.conversion.cloud.points.empty());
  }
  EXPECT_EQ(PointCloud2ScanType().failures(), 0u);
}

TEST(DdsPointCloud2ScanType, RefusesMalformedCdrAndRecordsIt) {
  sensor_msgs::msg::PointCloud2 msg = to_pointcloud2(sample_cloud(50, false), Stamp{}, "f");
  const rtps::SerializedPayload_t good = serialized(msg);
  PointCloud2ScanType type;
  ReceivedPointCloud2 scan;
  {
    // The generated type refuses the same bool (the checks below are the same as its).
    rtps::SerializedPayload_t bad_bool(good.length);
    std::memcpy(bad_bool.data, good.data, good.length);
    bad_bool.length = good.length;
    bad_bool.data[good.length - 1] = 2;
    CheckedType<sensor_msgs::msg::PointCloud2PubSubType> checked;
    sensor_msgs::msg::PointCloud2 read;
    EXPECT_FALSE(checked.deserialize(&bad_bool, &read));
  }
  take_sample_failures();

  // Every truncation of the payload: the data's length runs past the end, or a member is cut.
  for (std::uint32_t length : {good.length - 1, good.length - 2, good.length / 2, 30u, 5u}) {
    rtps::SerializedPayload_t cut(good.length);
    std::memcpy(cut.data, good.data, length);
    cut.length = length;
    EXPECT_FALSE(type.deserialize(&cut, &scan)) << length;
  }
  // is_dense, the payload's last byte, is a bool: 2 is not a valid encoding.
  rtps::SerializedPayload_t bad_bool(good.length);
  std::memcpy(bad_bool.data, good.data, good.length);
  bad_bool.length = good.length;
  bad_bool.data[good.length - 1] = 2;
  EXPECT_FALSE(type.deserialize(&bad_bool, &scan));
  // The data sequence's length field (the 4 bytes before the data) beyond the payload.
  rtps::SerializedPayload_t long_data(good.length);
  std::memcpy(long_data.data, good.data, good.length);
  long_data.length = good.length;
  const std::uint32_t data_bytes = static_cast<std::uint32_t>(msg.data().size());
  const std::uint32_t length_at = good.length - 1 - data_bytes - 4;
  std::uint32_t declared;
  std::memcpy(&declared, long_data.data + length_at, 4);
  ASSERT_EQ(declared, data_bytes);
  declared += 100;
  std::memcpy(long_data.data + length_at, &declared, 4);
  EXPECT_FALSE(type.deserialize(&long_data, &scan));

  const SampleFailures failed = take_sample_failures();
  EXPECT_EQ(failed.malformed, 7u);
  EXPECT_EQ(failed.last_error, SampleError::kMalformed);
  EXPECT_EQ(type.failures(), 7u);
}

TEST(DdsPointCloud2ScanType, RefusesPayloadsAboveTheLimit) {
  sensor_msgs::msg::PointCloud2 msg = to_pointcloud2(sample_cloud(50, false), Stamp{}, "f");
  rtps::SerializedPayload_t payload = serialized(msg);
  PointCloud2ScanType type(payload.length - 1);
  ReceivedPointCloud2 scan;
  take_sample_failures();
  EXPECT_FALSE(type.deserialize(&payload, &scan));
  const SampleFailures failed = take_sample_failures();
  EXPECT_EQ(failed.too_large, 1u);
  EXPECT_EQ(failed.last_error, SampleError::kTooLarge);
  PointCloud2ScanType unlimited;
  EXPECT_TRUE(unlimited.deserialize(&payload, &scan));
  EXPECT_TRUE(scan.conversion.ok());
}

}  // namespace
}  // namespace litamin2::dds

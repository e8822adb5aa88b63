/// Per-point times through the PointCloud2 conversion (CloudConversionOptions::read_time): each
/// vendor's layout as its ROS driver publishes it, relative and absolute times, and invalid
/// times rejected.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "litamin2/dds/pointcloud2_conversion.hpp"
#include "litamin2/dds/time_conversion.hpp"

namespace litamin2::dds {
namespace {

constexpr std::uint8_t kUint8 = 2;
constexpr std::uint8_t kUint16 = 4;
constexpr std::uint8_t kUint32 = 6;
constexpr std::uint8_t kFloat32 = 7;
constexpr std::uint8_t kFloat64 = 8;

sensor_msgs::msg::PointField field(const std::string& name, std::uint32_t offset,
                                   std::uint8_t datatype) {
  sensor_msgs::msg::PointField f;
  f.name(name);
  f.offset(offset);
  f.datatype(datatype);
  f.count(1);
  return f;
}

template <typename T>
void put(std::vector<std::uint8_t>& data, std::size_t at, T value) {
  std::memcpy(data.data() + at, &value, sizeof(T));
}

/// A sweep's points and their times: `n` points, time i * period / n (seconds from the stamp,
/// shifted by `offset_s`).
struct Sweep {
  std::vector<Eigen::Vector3f> points;
  std::vector<double> times;
};

Sweep sweep(std::size_t n, double offset_s = 0.0, unsigned seed = 3) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-60.0f, 60.0f);
  Sweep s;
  for (std::size_t i = 0; i < n; ++i) {
    s.points.emplace_back(u(rng), u(rng), u(rng));
    s.times.push_back(offset_s + 0.1 * static_cast<double>(i) / static_cast<double>(n));
  }
  return s;
}

/// A message with the driver's fields and point_step; `write_time` stores point i's time.
template <typename WriteTime>
sensor_msgs::msg::PointCloud2 message(const Sweep& s, std::vector<sensor_msgs::msg::PointField> f,
                                      std::uint32_t step, Stamp stamp, WriteTime write_time) {
  sensor_msgs::msg::PointCloud2 msg;
  msg.header().stamp(to_time(stamp));
  msg.height(1);
  msg.width(static_cast<std::uint32_t>(s.points.size()));
  msg.point_step(step);
  msg.row_step(step * msg.width());
  msg.is_bigendian(false);
  msg.fields(std::move(f));
  std::vector<std::uint8_t> data(msg.row_step(), 0x5A);
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    const std::size_t at = i * step;
    put<float>(data, at + 0, s.points[i].x());
    put<float>(data, at + 4, s.points[i].y());
    put<float>(data, at + 8, s.points[i].z());
    write_time(data, at, s.times[i]);
  }
  msg.data(std::move(data));
  return msg;
}

CloudConversion convert(const sensor_msgs::msg::PointCloud2& msg, bool read_time = true) {
  CloudConversionOptions options;
  options.read_time = read_time;
  return from_pointcloud2(msg, options);
}

void expect_times(const CloudConversion& c, const Sweep& s, double tolerance_s) {
  ASSERT_EQ(c.error, CloudError::kNone) << c.message;
  ASSERT_EQ(c.cloud.times.size(), s.times.size());
  ASSERT_EQ(c.cloud.points.size(), s.points.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < s.times.size(); ++i) {
    worst = std::max(worst, std::abs(double(c.cloud.times[i]) - s.times[i]));
    ASSERT_EQ(c.cloud.points[i], s.points[i]) << i;
  }
  EXPECT_LE(worst, tolerance_s);
}

const Stamp kStamp = Stamp::from_seconds(1733097600.25);  // 2024-12-02, as drivers stamp

/// ouster_ros PointXYZIRT-like point (48 bytes): x y z, intensity F32 at 16, t UINT32 ns at 20,
/// reflectivity and ring UINT16, ambient UINT16, range UINT32.
sensor_msgs::msg::PointCloud2 ouster(const Sweep& s) {
  return message(s,
                 {field("x", 0, kFloat32), field("y", 4, kFloat32), field("z", 8, kFloat32),
                  field("intensity", 16, kFloat32), field("t", 20, kUint32),
                  field("reflectivity", 24, kUint16), field("ring", 26, kUint16),
                  field("ambient", 28, kUint16), field("range", 32, kUint32)},
                 48, kStamp, [](std::vector<std::uint8_t>& d, std::size_t at, double t) {
                   put<std::uint32_t>(d, at + 20,
                                      static_cast<std::uint32_t>(std::llround(t * 1e9)));
                 });
}

TEST(DdsPointCloud2Time, OusterTUint32Nanoseconds) {
  const Sweep s = sweep(2048);
  const CloudConversion c = convert(ouster(s));
  expect_times(c, s, 1e-8);
  EXPECT_EQ(c.time_field, "t");
  EXPECT_FALSE(c.absolute_time);
}

/// velodyne_pointcloud PointXYZIRT (22 bytes, packed): x y z intensity F32, ring UINT16 at 16,
/// time FLOAT32 s at 18, relative to the stamp (negative when the stamp is the sweep's end).
sensor_msgs::msg::PointCloud2 velodyne(const Sweep& s) {
  return message(
      s,
      {field("x", 0, kFloat32), field("y", 4, kFloat32), field("z", 8, kFloat32),
       field("intensity", 12, kFloat32), field("ring", 16, kUint16), field("time", 18, kFloat32)},
      22, kStamp, [](std::vector<std::uint8_t>& d, std::size_t at, double t) {
        put<float>(d, at + 18, static_cast<float>(t));
      });
}

TEST(DdsPointCloud2Time, VelodyneTimeFloat32Seconds) {
  for (const double offset : {0.0, -0.1}) {
    const Sweep s = sweep(1800, offset);
    const CloudConversion c = convert(velodyne(s));
    expect_times(c, s, 1e-8);
    EXPECT_EQ(c.time_field, "time");
    EXPECT_FALSE(c.absolute_time);
    if (offset < 0.0) {
      EXPECT_LT(c.cloud.times.front(), -0.09f);
    }
  }
}

/// HesaiLidar_ROS_2.0 (26 bytes): x y z intensity F32, ring UINT16 at 16, timestamp FLOAT64 at
/// 18, absolute seconds since the epoch.
sensor_msgs::msg::PointCloud2 hesai(const Sweep& s, Stamp stamp = kStamp) {
  const double base = stamp.seconds();
  return message(s,
                 {field("x", 0, kFloat32), field("y", 4, kFloat32), field("z", 8, kFloat32),
                  field("intensity", 12, kFloat32), field("ring", 16, kUint16),
                  field("timestamp", 18, kFloat64)},
                 26, stamp, [base](std::vector<std::uint8_t>& d, std::size_t at, double t) {
                   put<double>(d, at + 18, base + t);
                 });
}

TEST(DdsPointCloud2Time, HesaiTimestampFloat64AbsoluteSeconds) {
  const Sweep s = sweep(1200);
  const CloudConversion c = convert(hesai(s));
  // A double holds today's epoch seconds to ~0.24 us.
  expect_times(c, s, 1e-6);
  EXPECT_EQ(c.time_field, "timestamp");
  EXPECT_TRUE(c.absolute_time);
}

TEST(DdsPointCloud2Time, Float64RelativeSecondsAndAbsoluteNanoseconds) {
  // A Hesai-like field holding relative seconds.
  const Sweep s = sweep(500);
  const auto relative = message(
      s,
      {field("x", 0, kFloat32), field("y", 4, kFloat32), field("z", 8, kFloat32),
       field("timestamp", 12, kFloat64)},
      20, kStamp,
      [](std::vector<std::uint8_t>& d, std::size_t at, double t) { put<double>(d, at + 12, t); });
  const CloudConversion r = convert(relative);
  expect_times(r, s, 1e-8);
  EXPECT_FALSE(r.absolute_time);
  // livox_ros_driver2's PointCloud2: timestamp FLOAT64 nanoseconds since the epoch.
  const double stamp_ns = static_cast<double>(kStamp.nanoseconds);
  const auto livox2 =
      message(s,
              {field("x", 0, kFloat32), field("y", 4, kFloat32), field("z", 8, kFloat32),
               field("intensity", 12, kFloat32), field("tag", 16, kUint8),
               field("line", 17, kUint8), field("timestamp", 18, kFloat64)},
              26, kStamp, [stamp_ns](std::vector<std::uint8_t>& d, std::size_t at, double t) {
                put<double>(d, at + 18, stamp_ns + std::round(t * 1e9));
              });
  const CloudConversion a = convert(livox2);
  expect_times(a, s, 1e-6);
  EXPECT_TRUE(a.absolute_time);
}

/// Livox (livox_ros_driver CustomPoint as PointCloud2, 22 bytes): x y z intensity F32, tag and
/// line UINT8 at 16 and 17, offset_time UINT32 ns from the stamp at 18.
sensor_msgs::msg::PointCloud2 livox(const Sweep& s) {
  return message(s,
                 {field("x", 0, kFloat32), field("y", 4, kFloat32), field("z", 8, kFloat32),
                  field("intensity", 12, kFloat32), field("tag", 16, kUint8),
                  field("line", 17, kUint8), field("offset_time", 18, kUint32)},
                 22, kStamp, [](std::vector<std::uint8_t>& d, std::size_t at, double t) {
                   put<std::uint32_t>(d, at + 18,
                                      static_cast<std::uint32_t>(std::llround(t * 1e9)));
                 });
}

TEST(DdsPointCloud2Time, LivoxOffsetTimeUint32Nanoseconds) {
  const Sweep s = sweep(960);
  const CloudConversion c = convert(livox(s));
  expect_times(c, s, 1e-8);
  EXPECT_EQ(c.time_field, "offset_time");
  EXPECT_FALSE(c.absolute_time);
}

TEST(DdsPointCloud2Time, WithoutReadTimeTheFieldIsIgnored) {
  const Sweep s = sweep(300);
  for (const auto& msg : {ouster(s), velodyne(s), hesai(s), livox(s)}) {
    const CloudConversion c = convert(msg, false);
    ASSERT_EQ(c.error, CloudError::kNone) << c.message;
    EXPECT_TRUE(c.cloud.times.empty());
    EXPECT_EQ(c.time_field, "");
    EXPECT_EQ(c.cloud.points, s.points);
  }
}

TEST(DdsPointCloud2Time, MessageWithoutTimeFieldHasNoTimes) {
  const Sweep s = sweep(100);
  const auto msg =
      message(s, {field("x", 0, kFloat32), field("y", 4, kFloat32), field("z", 8, kFloat32)}, 12,
              kStamp, [](std::vector<std::uint8_t>&, std::size_t, double) {});
  const CloudConversion c = convert(msg);
  ASSERT_EQ(c.error, CloudError::kNone) << c.message;
  EXPECT_TRUE(c.cloud.times.empty());
  EXPECT_EQ(c.time_field, "");
}

TEST(DdsPointCloud2Time, TimeOfADroppedPointIsDroppedWithIt) {
  Sweep s = sweep(50);
  s.points[7].x() = std::numeric_limits<float>::quiet_NaN();
  const CloudConversion c = convert(velodyne(s));
  ASSERT_EQ(c.error, CloudError::kNone) << c.message;
  EXPECT_EQ(c.non_finite, 1u);
  ASSERT_EQ(c.cloud.times.size(), 49u);
  EXPECT_FLOAT_EQ(c.cloud.times[7], static_cast<float>(s.times[8]));
}

TEST(DdsPointCloud2Time, InvalidTimesAreRejected) {
  const Sweep good = sweep(64);
  // Not finite.
  Sweep s = good;
  s.times[5] = std::numeric_limits<double>::quiet_NaN();
  CloudConversion c = convert(velodyne(s));
  EXPECT_EQ(c.error, CloudError::kBadTimeField);
  EXPECT_NE(c.message.find("non-finite"), std::string::npos) << c.message;
  EXPECT_TRUE(c.cloud.points.empty());
  EXPECT_TRUE(c.cloud.times.empty());
  s = good;
  s.times[5] = std::numeric_limits<double>::infinity();
  EXPECT_EQ(convert(hesai(s)).error, CloudError::kBadTimeField);
  // Out of the sweep: a relative time of 2 s (milliseconds read as seconds), an Ouster t of 3 s.
  s = good;
  s.times[9] = 2.0;
  EXPECT_EQ(convert(velodyne(s)).error, CloudError::kBadTimeField);
  EXPECT_EQ(convert(ouster(s)).error, CloudError::kBadTimeField);
  // Absolute times 5 s away from the stamp (another clock).
  s = good;
  const CloudConversion far = convert(hesai(s, Stamp::from_seconds(kStamp.seconds() + 5.0)));
  // hesai() writes times around its own stamp: move the header only.
  auto shifted = hesai(s);
  shifted.header().stamp(to_time(Stamp::from_seconds(kStamp.seconds() + 5.0)));
  EXPECT_EQ(far.error, CloudError::kNone) << far.message;
  EXPECT_EQ(convert(shifted).error, CloudError::kBadTimeField);
  // A malformed field: count 2, beyond point_step, a datatype that is not one.
  auto msg = velodyne(good);
  auto fields = msg.fields();
  fields.back().count(2);
  msg.fields(fields);
  EXPECT_EQ(convert(msg).error, CloudError::kBadTimeField);
  fields.back().count(1);
  fields.back().offset(20);
  msg.fields(fields);
  EXPECT_EQ(convert(msg).error, CloudError::kBadTimeField);
  fields.back().offset(18);
  fields.back().datatype(9);
  msg.fields(fields);
  EXPECT_EQ(convert(msg).error, CloudError::kBadTimeField);
  // The same field twice.
  fields.back().datatype(kFloat32);
  fields.push_back(field("time", 12, kFloat32));
  msg.fields(fields);
  EXPECT_EQ(convert(msg).error, CloudError::kBadTimeField);
  EXPECT_STREQ(to_string(CloudError::kBadTimeField), "bad_time_field");
}

TEST(DdsPointCloud2Time, ToPointCloud2WritesEachVendorsLayout) {
  const Sweep s = sweep(400);
  PointCloud cloud;
  cloud.points = s.points;
  for (const double t : s.times) cloud.times.push_back(static_cast<float>(t));
  for (const TimeLayout layout :
       {TimeLayout::kVelodyne, TimeLayout::kOuster, TimeLayout::kHesai, TimeLayout::kLivox}) {
    const auto msg = to_pointcloud2(cloud, kStamp, "lidar", layout);
    const CloudConversion c = convert(msg);
    ASSERT_EQ(c.error, CloudError::kNone) << to_string(layout) << ": " << c.message;
    const char* names[] = {"time", "t", "timestamp", "offset_time"};
    EXPECT_EQ(c.time_field, names[static_cast<int>(layout)]);
    EXPECT_EQ(c.absolute_time, layout == TimeLayout::kHesai);
    ASSERT_EQ(c.cloud.times.size(), cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i)
      ASSERT_NEAR(c.cloud.times[i], cloud.times[i], 1e-6) << to_string(layout) << " " << i;
    EXPECT_EQ(time_layout_from_string(to_string(layout)), layout);
  }
  EXPECT_FALSE(time_layout_from_string("sick").has_value());
  // Unsigned nanoseconds hold no time before the stamp; invalid times are refused.
  PointCloud before = cloud;
  before.times[0] = -0.01f;
  EXPECT_THROW(to_pointcloud2(before, kStamp, "lidar", TimeLayout::kOuster), std::invalid_argument);
  EXPECT_NO_THROW(to_pointcloud2(before, kStamp, "lidar", TimeLayout::kVelodyne));
  before.times[0] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(to_pointcloud2(before, kStamp, "lidar"), std::invalid_argument);
}

}  // namespace
}  // namespace litamin2::dds

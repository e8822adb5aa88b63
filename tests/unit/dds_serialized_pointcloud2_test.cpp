/// SerializedPointCloud2: a scan serialised once is published byte for byte as the generated type
/// would write it, and reads back as the same message.

#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "litamin2/dds/pointcloud2_conversion.hpp"
#include "litamin2/dds/serialized_pointcloud2.hpp"
#include "sensor_msgs/msg/PointCloud2PubSubTypes.h"

namespace litamin2::dds {
namespace {

namespace rtps = eprosima::fastrtps::rtps;

sensor_msgs::msg::PointCloud2 sample_message(std::size_t points) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-50.0f, 50.0f);
  PointCloud cloud;
  for (std::size_t i = 0; i < points; ++i) {
    cloud.points.emplace_back(u(rng), u(rng), u(rng));
    cloud.intensities.push_back(0.25f);
  }
  return to_pointcloud2(cloud, Stamp::from_seconds(12.5), "car_7");
}

TEST(DdsSerializedPointCloud2, PublishesTheGeneratedTypesBytes) {
  sensor_msgs::msg::PointCloud2 msg = sample_message(1000);
  sensor_msgs::msg::PointCloud2PubSubType generated;
  rtps::SerializedPayload_t expected(generated.getSerializedSizeProvider(&msg)());
  ASSERT_TRUE(generated.serialize(&msg, &expected));

  SerializedPointCloud2 scan = serialize_pointcloud2(msg);
  EXPECT_EQ(scan.points, 1000u);
  EXPECT_EQ(scan.data_bytes, msg.data().size());
  SerializedPointCloud2Type type;
  EXPECT_STREQ(type.getName(), generated.getName());
  EXPECT_EQ(type.getSerializedSizeProvider(&scan)(), expected.length);

  rtps::SerializedPayload_t written(type.getSerializedSizeProvider(&scan)());
  ASSERT_TRUE(type.serialize(&scan, &written));
  ASSERT_EQ(written.length, expected.length);
  EXPECT_EQ(std::memcmp(written.data, expected.data, expected.length), 0);
  EXPECT_EQ(written.encapsulation, expected.encapsulation);

  // What a reader of the generated type takes from those bytes is the message itself.
  sensor_msgs::msg::PointCloud2 read;
  ASSERT_TRUE(generated.deserialize(&written, &read));
  EXPECT_EQ(read, msg);
}

TEST(DdsSerializedPointCloud2, RefusesAPayloadTooSmallAndReadsNothing) {
  sensor_msgs::msg::PointCloud2 msg = sample_message(100);
  SerializedPointCloud2 scan = serialize_pointcloud2(msg);
  SerializedPointCloud2Type type;
  rtps::SerializedPayload_t small(static_cast<std::uint32_t>(scan.cdr.size() - 1));
  EXPECT_FALSE(type.serialize(&scan, &small));
  SerializedPointCloud2 empty;
  rtps::SerializedPayload_t payload(64);
  EXPECT_FALSE(type.serialize(&empty, &payload));
  // Publishing only: nothing deserialises into it, and there is no key.
  void* data = type.createData();
  EXPECT_FALSE(type.deserialize(&payload, data));
  rtps::InstanceHandle_t handle;
  EXPECT_FALSE(type.getKey(data, &handle));
  type.deleteData(data);
}

}  // namespace
}  // namespace litamin2::dds

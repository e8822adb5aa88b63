// The map's points as sensor_msgs/PointCloud2 (aggregator/dds/map_cloud_message.hpp): the
// layout (x, y, z FLOAT32, count UINT32, 16 bytes a point), and the project's own validated
// reader gets the points back.

#include "litamin2/aggregator/dds/map_cloud_message.hpp"
#include "litamin2/dds/pointcloud2_conversion.hpp"

#include <gtest/gtest.h>

#include <cstring>

using namespace litamin2;
using namespace litamin2::aggregator;

TEST(MapCloudMessage, LayoutAndRoundTrip) {
  const std::vector<MapPoint> points = {{1.5f, -2.0f, 0.25f, 7u}, {100.0f, 200.0f, -3.0f, 42u}};
  const sensor_msgs::msg::PointCloud2 msg =
      to_map_cloud_msg(points, Stamp::from_seconds(1000.25), "map");
  EXPECT_EQ(msg.header().frame_id(), "map");
  EXPECT_EQ(msg.header().stamp().sec(), 1000);
  EXPECT_EQ(msg.header().stamp().nanosec(), 250000000u);
  EXPECT_EQ(msg.width(), 2u);
  EXPECT_EQ(msg.height(), 1u);
  EXPECT_EQ(msg.point_step(), 16u);
  EXPECT_EQ(msg.row_step(), 32u);
  ASSERT_EQ(msg.fields().size(), 4u);
  EXPECT_EQ(msg.fields()[3].name(), "count");
  EXPECT_EQ(msg.fields()[3].offset(), 12u);
  EXPECT_EQ(msg.fields()[3].datatype(), 6);                              // UINT32
  for (int i = 0; i < 3; ++i) EXPECT_EQ(msg.fields()[i].datatype(), 7);  // FLOAT32
  std::uint32_t count = 0;
  std::memcpy(&count, msg.data().data() + 16 + 12, 4);
  EXPECT_EQ(count, 42u);

  const dds::CloudConversion back = dds::from_pointcloud2(msg);
  ASSERT_TRUE(back.ok()) << back.message;
  ASSERT_EQ(back.cloud.size(), 2u);
  EXPECT_EQ(back.cloud.points[0].x(), 1.5f);
  EXPECT_EQ(back.cloud.points[1].y(), 200.0f);
  EXPECT_EQ(back.cloud.points[1].z(), -3.0f);

  const sensor_msgs::msg::PointCloud2 empty = to_map_cloud_msg({}, Stamp{}, "map");
  EXPECT_EQ(empty.width(), 0u);
  EXPECT_TRUE(dds::from_pointcloud2(empty).ok());
}

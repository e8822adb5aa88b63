#include "litamin2/aggregator/dds/map_cloud_message.hpp"

#include "litamin2/dds/time_conversion.hpp"

#include <cstring>

namespace litamin2::aggregator {

namespace {

constexpr std::uint8_t kFloat32 = 7;  // sensor_msgs/PointField FLOAT32
constexpr std::uint8_t kUint32 = 6;   // sensor_msgs/PointField UINT32
constexpr std::uint32_t kPointStep = 16;

sensor_msgs::msg::PointField field(const char* name, std::uint32_t offset, std::uint8_t type) {
  sensor_msgs::msg::PointField f;
  f.name(name);
  f.offset(offset);
  f.datatype(type);
  f.count(1);
  return f;
}

}  // namespace

sensor_msgs::msg::PointCloud2 to_map_cloud_msg(const std::vector<MapPoint>& points, Stamp stamp,
                                               const std::string& frame_id) {
  static_assert(sizeof(MapPoint) == kPointStep, "MapPoint is the PointCloud2 record");
  sensor_msgs::msg::PointCloud2 msg;
  msg.header().stamp(dds::to_time(stamp));
  msg.header().frame_id(frame_id);
  msg.height(1);
  msg.width(static_cast<std::uint32_t>(points.size()));
  msg.fields({field("x", 0, kFloat32), field("y", 4, kFloat32), field("z", 8, kFloat32),
              field("count", 12, kUint32)});
  // The records are copied as they are in memory: the host's byte order.
  msg.is_bigendian(__BYTE_ORDER__ == __ORDER_BIG_ENDIAN__);
  msg.point_step(kPointStep);
  msg.row_step(static_cast<std::uint32_t>(kPointStep * points.size()));
  msg.data().resize(kPointStep * points.size());
  if (!points.empty()) std::memcpy(msg.data().data(), points.data(), msg.data().size());
  msg.is_dense(true);
  return msg;
}

}  // namespace litamin2::aggregator

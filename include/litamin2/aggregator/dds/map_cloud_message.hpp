#pragma once
/// The global map's points (map_cloud.hpp) as sensor_msgs/PointCloud2: fields x, y, z (FLOAT32,
/// offsets 0, 4, 8) and count (UINT32, offset 12), point_step 16, one row, little-endian, dense.

#include "litamin2/aggregator/map_cloud.hpp"
#include "litamin2/core/stamp.hpp"
#include "sensor_msgs/msg/PointCloud2.h"

#include <string>
#include <vector>

namespace litamin2::aggregator {

sensor_msgs::msg::PointCloud2 to_map_cloud_msg(const std::vector<MapPoint>& points, Stamp stamp,
                                               const std::string& frame_id);

}  // namespace litamin2::aggregator

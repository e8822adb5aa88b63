#pragma once
/// A PointCloud2 serialised to CDR once, and the DDS type that publishes such bytes as they are.
///
/// rosbag2 replays serialised messages; so does `litamin2-replay --preload`: each scan is
/// converted and serialised before publishing starts, and a write then only copies the stored
/// bytes into Fast DDS's payload. `SerializedPointCloud2Type` has the registered name of
/// sensor_msgs/PointCloud2 (readers of any vendor match it as that type); it can only write.

#include <cstdint>
#include <vector>

#include <fastdds/dds/topic/TopicDataType.hpp>

#include "sensor_msgs/msg/PointCloud2.h"

namespace litamin2::dds {

/// One scan's CDR bytes, encapsulation header included, as the generated type writes them.
struct SerializedPointCloud2 {
  std::vector<unsigned char> cdr;
  std::uint64_t points = 0;
  std::uint64_t data_bytes = 0;  ///< size of the message's point data (PointCloud2::data)
};

/// Serialises `msg` with the generated type support. Throws std::runtime_error if it cannot.
SerializedPointCloud2 serialize_pointcloud2(sensor_msgs::msg::PointCloud2& msg);

class SerializedPointCloud2Type : public eprosima::fastdds::dds::TopicDataType {
 public:
  SerializedPointCloud2Type();

  /// Copies the stored bytes of a SerializedPointCloud2 into `payload`; false if they do not fit.
  bool serialize(void* data, eprosima::fastrtps::rtps::SerializedPayload_t* payload) override;
  /// Always false: this type only publishes.
  bool deserialize(eprosima::fastrtps::rtps::SerializedPayload_t* payload, void* data) override;
  std::function<uint32_t()> getSerializedSizeProvider(void* data) override;
  void* createData() override;
  void deleteData(void* data) override;
  /// PointCloud2 has no key.
  bool getKey(void* data, eprosima::fastrtps::rtps::InstanceHandle_t* handle,
              bool force_md5 = false) override;
};

}  // namespace litamin2::dds

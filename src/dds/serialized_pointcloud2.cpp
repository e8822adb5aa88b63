#include "litamin2/dds/serialized_pointcloud2.hpp"

#include <cstring>
#include <stdexcept>

#include "sensor_msgs/msg/PointCloud2PubSubTypes.h"

namespace litamin2::dds {

namespace rtps = eprosima::fastrtps::rtps;

SerializedPointCloud2 serialize_pointcloud2(sensor_msgs::msg::PointCloud2& msg) {
  sensor_msgs::msg::PointCloud2PubSubType type;
  rtps::SerializedPayload_t payload(type.getSerializedSizeProvider(&msg)());
  if (!type.serialize(&msg, &payload)) {
    throw std::runtime_error("a PointCloud2 of " + std::to_string(msg.data().size()) +
                             " data bytes could not be serialised");
  }
  SerializedPointCloud2 scan;
  scan.cdr.assign(payload.data, payload.data + payload.length);
  scan.points = static_cast<std::uint64_t>(msg.width()) * msg.height();
  scan.data_bytes = msg.data().size();
  return scan;
}

SerializedPointCloud2Type::SerializedPointCloud2Type() {
  // The same name and payload bound as the generated type: readers see sensor_msgs/PointCloud2.
  const sensor_msgs::msg::PointCloud2PubSubType generated;
  setName(generated.getName());
  m_typeSize = generated.m_typeSize;
  m_isGetKeyDefined = false;
}

bool SerializedPointCloud2Type::serialize(void* data, rtps::SerializedPayload_t* payload) {
  const auto& scan = *static_cast<const SerializedPointCloud2*>(data);
  // The first two bytes are the encapsulation identifier (RTPS 9.4.2.12): 0x0001 is CDR_LE.
  if (scan.cdr.size() < 4 || scan.cdr.size() > payload->max_size) return false;
  std::memcpy(payload->data, scan.cdr.data(), scan.cdr.size());
  payload->length = static_cast<std::uint32_t>(scan.cdr.size());
  payload->encapsulation = scan.cdr[1] == 0x01 ? CDR_LE : CDR_BE;
  return true;
}

bool SerializedPointCloud2Type::deserialize(rtps::SerializedPayload_t*, void*) {
  return false;
}

std::function<uint32_t()> SerializedPointCloud2Type::getSerializedSizeProvider(void* data) {
  return [data] {
    return static_cast<std::uint32_t>(static_cast<const SerializedPointCloud2*>(data)->cdr.size());
  };
}

void* SerializedPointCloud2Type::createData() {
  return new SerializedPointCloud2();
}

void SerializedPointCloud2Type::deleteData(void* data) {
  delete static_cast<SerializedPointCloud2*>(data);
}

bool SerializedPointCloud2Type::getKey(void*, rtps::InstanceHandle_t*, bool) {
  return false;
}

}  // namespace litamin2::dds

#include "litamin2/dds/pointcloud2_scan_type.hpp"

#include <exception>
#include <string>

#include <fastcdr/Cdr.h>
#include <fastcdr/FastBuffer.h>
#include <fastcdr/exceptions/Exception.h>

#include "litamin2/dds/checked_type.hpp"
#include "sensor_msgs/msg/PointCloud2PubSubTypes.h"

namespace litamin2::dds {

namespace rtps = eprosima::fastrtps::rtps;
namespace fastcdr = eprosima::fastcdr;

PointCloud2ScanType::PointCloud2ScanType(std::uint32_t max_payload_bytes)
    : max_payload_bytes_(max_payload_bytes) {
  // The generated type's name and payload bound: writers see sensor_msgs/PointCloud2.
  const sensor_msgs::msg::PointCloud2PubSubType generated;
  setName(generated.getName());
  m_typeSize = generated.m_typeSize;
  m_isGetKeyDefined = false;
}

bool PointCloud2ScanType::serialize(void*, rtps::SerializedPayload_t*) {
  return false;
}

bool PointCloud2ScanType::deserialize(rtps::SerializedPayload_t* payload, void* data) {
  auto fail = [this](SampleError error, std::string message) {
    ++failures_;
    record_sample_failure(error, std::move(message));
    return false;
  };
  if (max_payload_bytes_ > 0 && payload->length > max_payload_bytes_) {
    return fail(SampleError::kTooLarge, std::to_string(payload->length) + " bytes > limit " +
                                            std::to_string(max_payload_bytes_));
  }
  auto& scan = *static_cast<ReceivedPointCloud2*>(data);
  auto& m = scan.meta;
  const unsigned char* points = nullptr;
  std::uint32_t points_size = 0;
  try {
    fastcdr::FastBuffer buffer(reinterpret_cast<char*>(payload->data), payload->length);
    fastcdr::Cdr cdr(buffer, fastcdr::Cdr::DEFAULT_ENDIAN, fastcdr::Cdr::DDS_CDR);
    cdr.read_encapsulation();
    payload->encapsulation = cdr.endianness() == fastcdr::Cdr::BIG_ENDIANNESS ? CDR_BE : CDR_LE;
    // The members in the IDL's order (idl/sensor_msgs/msg/PointCloud2.idl), as the generated
    // PointCloud2::deserialize reads them, but for the data sequence: its length, then its
    // bytes are skipped (an octet sequence has no alignment after its length).
    cdr >> m.header();
    cdr >> m.height();
    cdr >> m.width();
    cdr >> m.fields();
    cdr >> m.is_bigendian();
    cdr >> m.point_step();
    cdr >> m.row_step();
    cdr >> points_size;
    points = reinterpret_cast<const unsigned char*>(cdr.getCurrentPosition());
    if (!cdr.jump(points_size)) {
      throw fastcdr::exception::NotEnoughMemoryException(
          "the data sequence's length is beyond the payload");
    }
    cdr >> m.is_dense();
  } catch (const fastcdr::exception::Exception& e) {
    return fail(SampleError::kMalformed, e.what());
  } catch (const std::exception& e) {
    return fail(SampleError::kMalformed, e.what());
  }
  m.data().clear();
  from_pointcloud2(m, points, points_size, scan.options, scan.conversion);
  return true;
}

std::function<uint32_t()> PointCloud2ScanType::getSerializedSizeProvider(void*) {
  return [] { return 0u; };
}

void* PointCloud2ScanType::createData() {
  return new ReceivedPointCloud2();
}

void PointCloud2ScanType::deleteData(void* data) {
  delete static_cast<ReceivedPointCloud2*>(data);
}

bool PointCloud2ScanType::getKey(void*, rtps::InstanceHandle_t*, bool) {
  return false;
}

}  // namespace litamin2::dds

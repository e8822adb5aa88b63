#pragma once
/// The reader side's sensor_msgs/PointCloud2 type: deserialisation that converts the point data
/// where it lies in the received payload.
///
/// The generated type copies the message's data sequence (~1.5 MB for an HDL-64 scan) out of
/// Fast DDS's history into a fresh std::vector, and from_pointcloud2 then reads that copy into
/// the tracker's points. PointCloud2ScanType reads every other member with fastcdr exactly as
/// the generated code does (same order, same checks: a bool byte other than 0 or 1, a length
/// beyond the payload or a truncated payload is malformed), skips over the data sequence and
/// runs from_pointcloud2 on its bytes in the payload: one pass over the data instead of a copy
/// and a pass, and no per-frame buffer of the data's size. It keeps CheckedType's contract:
/// deserialize() never throws, refuses payloads above the size limit, and records why on the
/// calling thread (take_sample_failures) and on the type (failures()). A message that
/// deserialises but fails the conversion's checks is delivered, its `conversion.error` set.
/// Its registered name is sensor_msgs/PointCloud2's, so writers of any vendor match it; it
/// can only read.

#include <atomic>
#include <cstdint>

#include <fastdds/dds/topic/TopicDataType.hpp>

#include "litamin2/dds/pointcloud2_conversion.hpp"
#include "sensor_msgs/msg/PointCloud2.h"

namespace litamin2::dds {

/// A sample of PointCloud2ScanType: the conversion's options (set before take) and its result.
struct ReceivedPointCloud2 {
  /// Input: how to convert (intensity, times, point limit).
  CloudConversionOptions options;
  /// The message's members but its point data (`meta.data()` stays empty).
  sensor_msgs::msg::PointCloud2 meta;
  /// The converted points or why the message was rejected, as from_pointcloud2 gives them.
  CloudConversion conversion;
};

class PointCloud2ScanType : public eprosima::fastdds::dds::TopicDataType {
 public:
  /// `max_payload_bytes`: larger payloads are refused as too large (0: no limit).
  explicit PointCloud2ScanType(std::uint32_t max_payload_bytes = 0);

  /// Always false: this type only reads.
  bool serialize(void* data, eprosima::fastrtps::rtps::SerializedPayload_t* payload) override;
  /// Reads the payload into a ReceivedPointCloud2 and converts its points (see above).
  bool deserialize(eprosima::fastrtps::rtps::SerializedPayload_t* payload, void* data) override;
  std::function<uint32_t()> getSerializedSizeProvider(void* data) override;
  void* createData() override;
  void deleteData(void* data) override;
  /// PointCloud2 has no key.
  bool getKey(void* data, eprosima::fastrtps::rtps::InstanceHandle_t* handle,
              bool force_md5 = false) override;

  /// Samples that could not be deserialised so far.
  std::uint64_t failures() const { return failures_.load(); }

 private:
  const std::uint32_t max_payload_bytes_;
  std::atomic<std::uint64_t> failures_{0};
};

}  // namespace litamin2::dds

// Fuzz harness: a sensor_msgs/PointCloud2 as litamin2d receives it, from raw CDR bytes through
// the reader's dds::CheckedType to dds::from_pointcloud2 (with and without intensities, with
// and without the per-point time fields that deskew reads).
// Properties: nothing throws; a rejected cloud is empty with a reason; an accepted one holds
// only finite points and finite intensities, valid times only when they were asked for (one
// per point, finite, within the sweep bound), accounts for every point (kept + non-finite ==
// width * height), and converts back to a message that gives the same points.

#include "cdr_payload.hpp"
#include "fuzz_support.hpp"
#include "litamin2/dds/pointcloud2_conversion.hpp"
#include "sensor_msgs/msg/PointCloud2PubSubTypes.h"

using namespace litamin2;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static dds::CheckedType<sensor_msgs::msg::PointCloud2PubSubType> type;
  sensor_msgs::msg::PointCloud2 msg;
  if (!fuzz::deserialize(type, data, size, msg)) return 0;
  for (const bool with_times : {false, true}) {
    for (const bool with_intensity : {true, false}) {
      dds::CloudConversionOptions options;
      options.read_intensity = with_intensity;
      options.read_time = with_times;
      options.max_points = 1 << 20;
      const dds::CloudConversion c = dds::from_pointcloud2(msg, options);
      if (!c.ok()) {
        LITAMIN2_FUZZ_CHECK(c.cloud.points.empty() && !c.message.empty(),
                            "rejected: empty, reason");
        continue;
      }
      fuzz::check_cloud(c.cloud);
      LITAMIN2_FUZZ_CHECK(with_times || c.cloud.times.empty(), "no times when off");
      LITAMIN2_FUZZ_CHECK(!point_times_error(c.cloud), "times valid");
      if (with_intensity && !with_times) fuzz::accepted() = true;
      LITAMIN2_FUZZ_CHECK(c.cloud.size() + c.non_finite == c.total_points, "every point counted");
      LITAMIN2_FUZZ_CHECK(with_intensity || c.cloud.intensities.empty(), "no intensity when off");
      const dds::CloudConversion again =
          dds::from_pointcloud2(dds::to_pointcloud2(c.cloud, Stamp{}, "f"), options);
      LITAMIN2_FUZZ_CHECK(again.ok() && again.cloud.points == c.cloud.points, "round trip");
    }
  }
  return 0;
}

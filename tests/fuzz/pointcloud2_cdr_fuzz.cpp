// Fuzz harness: a sensor_msgs/PointCloud2 as litamin2d receives it, from raw CDR bytes through
// the reader's dds::CheckedType to dds::from_pointcloud2 (with and without intensities, with
// and without the per-point time fields that deskew reads).
// Properties: nothing throws; a rejected cloud is empty with a reason; an accepted one holds
// only finite points and finite intensities, valid times only when they were asked for (one
// per point, finite, within the sweep bound), accounts for every point (kept + non-finite ==
// width * height), and converts back to a message that gives the same points. The daemon's own
// reader type, dds::PointCloud2ScanType (converting the data where it lies in the payload), is
// run on the same bytes with the same options: it must refuse exactly what the generated type
// refuses and otherwise give the same conversion (error, reason, points, counters).

#include "cdr_payload.hpp"
#include "fuzz_support.hpp"
#include "litamin2/dds/pointcloud2_conversion.hpp"
#include "litamin2/dds/pointcloud2_scan_type.hpp"
#include "sensor_msgs/msg/PointCloud2PubSubTypes.h"

using namespace litamin2;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static dds::CheckedType<sensor_msgs::msg::PointCloud2PubSubType> type;
  static dds::PointCloud2ScanType scan_type;
  sensor_msgs::msg::PointCloud2 msg;
  const bool deserialised = fuzz::deserialize(type, data, size, msg);
  dds::ReceivedPointCloud2 scan;
  LITAMIN2_FUZZ_CHECK(fuzz::deserialize(scan_type, data, size, scan) == deserialised,
                      "in-place type refuses what the generated type refuses");
  if (!deserialised) return 0;
  for (const bool with_times : {false, true}) {
    for (const bool with_intensity : {true, false}) {
      dds::CloudConversionOptions options;
      options.read_intensity = with_intensity;
      options.read_time = with_times;
      options.max_points = 1 << 20;
      const dds::CloudConversion c = dds::from_pointcloud2(msg, options);
      scan.options = options;
      LITAMIN2_FUZZ_CHECK(fuzz::deserialize(scan_type, data, size, scan), "in-place type reads");
      const dds::CloudConversion& in_place = scan.conversion;
      LITAMIN2_FUZZ_CHECK(in_place.error == c.error && in_place.message == c.message &&
                              in_place.cloud.points == c.cloud.points &&
                              in_place.cloud.intensities == c.cloud.intensities &&
                              in_place.cloud.times == c.cloud.times &&
                              in_place.non_finite == c.non_finite &&
                              in_place.total_points == c.total_points,
                          "in-place conversion == generated type + from_pointcloud2");
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

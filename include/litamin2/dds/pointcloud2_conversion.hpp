#pragma once
/// sensor_msgs/PointCloud2 <-> litamin2::PointCloud, with the field-by-field validation of
/// DESIGN.md section 4. The checks never throw and never read outside the message's data.

#include <cstddef>
#include <cstdint>
#include <string>

#include "litamin2/core/point_cloud.hpp"
#include "litamin2/core/stamp.hpp"
#include "sensor_msgs/msg/PointCloud2.h"

namespace litamin2::dds {

/// Why a PointCloud2 was rejected.
enum class CloudError {
  kNone = 0,
  /// No field named x, y or z.
  kMissingField,
  /// A field named x, y, z or intensity appears more than once.
  kDuplicateField,
  /// x, y or z is not FLOAT32/FLOAT64, or intensity has a datatype code outside 1..8, or one
  /// of them has count 0.
  kBadFieldType,
  /// A field of x, y, z, intensity does not fit in point_step (offset + size * count); this
  /// includes point_step 0.
  kFieldOutOfBounds,
  /// row_step < width * point_step.
  kBadRowStep,
  /// data.size() != row_step * height (truncated or trailing bytes).
  kDataSizeMismatch,
  /// width * height > max_points.
  kTooManyPoints,
  /// header.stamp.nanosec >= 1e9.
  kBadStamp,
  /// A point with finite coordinates has a NaN or +-Inf intensity (when intensities are read).
  kNonFiniteIntensity,
};

/// Short name of an error ("missing_field", ...), for counters and logs.
const char* to_string(CloudError error);

/// Options of from_pointcloud2.
struct CloudConversionOptions {
  /// Clouds with more points (width * height, before dropping non-finite points) are rejected
  /// with kTooManyPoints; 0 means no limit. The daemon's limits.max_points_per_scan.
  std::size_t max_points = 5'000'000;
  /// Read the "intensity" field when present (any numeric datatype, converted to float).
  bool read_intensity = true;
};

/// Result of from_pointcloud2.
struct CloudConversion {
  CloudError error = CloudError::kNone;
  /// Human-readable reason when error != kNone ("row_step 100 < width 10 * point_step 16").
  std::string message;
  /// The finite points of the message, in data order (rows then columns); intensities when
  /// the message has an intensity field and read_intensity is set. Empty when rejected.
  PointCloud cloud;
  /// Points dropped because a coordinate was NaN or +-Inf (after conversion to float).
  std::size_t non_finite = 0;
  /// The message's width * height.
  std::size_t total_points = 0;

  bool ok() const { return error == CloudError::kNone; }
};

/// Converts and validates a PointCloud2:
///  - x, y, z must each appear exactly once, FLOAT32 or FLOAT64, at any offset with
///    offset + size <= point_step (so fields may be interleaved with others in any order);
///  - "intensity" is optional, any numeric PointField datatype; other fields are ignored;
///  - row_step >= width * point_step, and data.size()
///    == row_step * height exactly (a truncated or padded buffer means the header is wrong);
///  - width * height == 0 is a valid empty cloud;
///  - is_bigendian: values are byte-swapped when the message's byte order differs from the
///    host's (not rejected);
///  - points with a NaN/Inf coordinate are dropped and counted in `non_finite` (the "no
///    return" points of organised clouds); is_dense is ignored;
///  - a point with finite coordinates and a NaN/Inf intensity rejects the message
///    (kNonFiniteIntensity): it is not repaired to 0.
/// Never throws for bad input (only std::bad_alloc can escape), never reads out of bounds.
CloudConversion from_pointcloud2(const sensor_msgs::msg::PointCloud2& msg,
                                 const CloudConversionOptions& options = {});

/// Same as above, writing into `out` (reusing its capacity); returns the error, fills the
/// counters and message of `out`.
CloudError from_pointcloud2(const sensor_msgs::msg::PointCloud2& msg,
                            const CloudConversionOptions& options, CloudConversion& out);

/// A dense, unordered (height 1), host-byte-order PointCloud2 with FLOAT32 fields x (offset 0),
/// y (4), z (8), intensity (12), point_step 16, row_step 16 * width; intensity is 0 when the
/// cloud has none. header.stamp = stamp, header.frame_id = frame_id.
sensor_msgs::msg::PointCloud2 to_pointcloud2(const PointCloud& cloud, Stamp stamp,
                                             const std::string& frame_id);

}  // namespace litamin2::dds

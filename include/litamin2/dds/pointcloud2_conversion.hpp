#pragma once
/// sensor_msgs/PointCloud2 <-> litamin2::PointCloud, with the field-by-field validation of
/// DESIGN.md section 4. The checks never throw and never read outside the message's data.

#include <cstddef>
#include <cstdint>
#include <optional>
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
  /// With read_time: the per-point time field cannot be used: it appears twice, its datatype
  /// is not 1..8 or its count not 1, it does not fit in point_step, a point's time is not
  /// finite, or the times are neither relative (within 1 s of 0) nor, for a FLOAT64 field,
  /// absolute (within 1 s of header.stamp, in seconds or nanoseconds).
  kBadTimeField,
  /// A point with finite coordinates has a NaN or +-Inf intensity (when intensities are read).
  kNonFiniteIntensity,
  /// A litamin2_zero_copy/PlainScan's frame_id has no NUL within its array
  /// (plain_scan_conversion.hpp).
  kBadFrameId,
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
  /// Read the per-point time into PointCloud::times (seconds relative to header.stamp), from
  /// the first of these fields the message has, as drivers publish them: `t` (Ouster, UINT32
  /// ns), `time` (Velodyne, FLOAT32 s), `timestamp` (Hesai, FLOAT64 s, absolute or relative),
  /// `offset_time` (Livox, UINT32 ns). Integer datatypes are nanoseconds, FLOAT32/FLOAT64
  /// seconds. Times within +-1 s are relative to the stamp; a FLOAT64 field may instead hold
  /// absolute times within 1 s of the stamp, in seconds or (livox_ros_driver2) nanoseconds
  /// since the epoch, which are made relative. (With a stamp under 2 s, synthetic data, the
  /// relative reading wins.) A message without a time field converts without times; a
  /// malformed one is rejected with kBadTimeField. Without read_time, time fields are ignored.
  bool read_time = false;
};

/// Result of from_pointcloud2.
struct CloudConversion {
  CloudError error = CloudError::kNone;
  /// Human-readable reason when error != kNone ("row_step 100 < width 10 * point_step 16").
  std::string message;
  /// The finite points of the message, in data order (rows then columns); intensities when
  /// the message has an intensity field and read_intensity is set; times when it has a time
  /// field and read_time is set. Empty when rejected.
  PointCloud cloud;
  /// With read_time: the time field read ("" if none), and whether its values were absolute.
  std::string time_field;
  bool absolute_time = false;
  /// Points dropped because a coordinate was NaN or +-Inf (after conversion to float).
  std::size_t non_finite = 0;
  /// The message's width * height.
  std::size_t total_points = 0;

  bool ok() const { return error == CloudError::kNone; }
  /// Records a rejection: sets error and message and empties the cloud; returns error.
  CloudError reject(CloudError why, std::string reason);
};

/// Converts and validates a PointCloud2:
///  - x, y, z must each appear exactly once, FLOAT32 or FLOAT64, at any offset with
///    offset + size <= point_step (so fields may be interleaved with others in any order);
///  - "intensity" is optional, any numeric PointField datatype; with options.read_time, so is
///    a time field (t, time, timestamp or offset_time, see read_time); other fields are ignored;
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

/// Same as above with the point data given apart: `msg.data()` is ignored and the `data_size`
/// bytes at `data` are read in its place, with the same checks (data_size must be row_step *
/// height). PointCloud2ScanType uses it to convert the data sequence where it lies in the
/// serialised payload, without copying it into a message first.
CloudError from_pointcloud2(const sensor_msgs::msg::PointCloud2& msg, const std::uint8_t* data,
                            std::size_t data_size, const CloudConversionOptions& options,
                            CloudConversion& out);

/// How to_pointcloud2 writes a cloud's per-point times, as one vendor's driver does.
enum class TimeLayout {
  /// `time` FLOAT32 seconds relative to the stamp (Velodyne): exact for the cloud's floats.
  kVelodyne,
  /// `t` UINT32 nanoseconds from the stamp (Ouster); times must not be negative.
  kOuster,
  /// `timestamp` FLOAT64 absolute seconds since the epoch (Hesai).
  kHesai,
  /// `offset_time` UINT32 nanoseconds from the stamp (Livox); times must not be negative.
  kLivox,
};

/// A dense, unordered (height 1), host-byte-order PointCloud2 with FLOAT32 fields x (offset 0),
/// y (4), z (8), intensity (12), point_step 16, row_step 16 * width; intensity is 0 when the
/// cloud has none. When the cloud has per-point times, a time field in `layout` follows at
/// offset 16 (point_step 20, or 24 for kHesai). header.stamp = stamp, header.frame_id =
/// frame_id. Throws std::invalid_argument for times that are invalid (point_times_error) or
/// negative with an unsigned layout.
sensor_msgs::msg::PointCloud2 to_pointcloud2(const PointCloud& cloud, Stamp stamp,
                                             const std::string& frame_id,
                                             TimeLayout layout = TimeLayout::kVelodyne);

/// Layout names for options: "velodyne", "ouster", "hesai", "livox".
const char* to_string(TimeLayout layout);
/// The layout of a name of to_string(TimeLayout), or nothing.
std::optional<TimeLayout> time_layout_from_string(const std::string& name);

}  // namespace litamin2::dds

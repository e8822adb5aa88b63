#pragma once
/// litamin2_zero_copy/PlainScan (idl/litamin2_zero_copy/msg/PlainScan.idl) <->
/// litamin2::PointCloud: the fixed-size scan of the same-host zero-copy input. from_plain_scan
/// reads the sample where it lies (a loaned sample in Fast DDS's data-sharing pool) and checks it
/// as from_pointcloud2 checks a PointCloud2; it never throws for bad input and never reads outside
/// the sample.

#include <cstdint>
#include <string>

#include "litamin2/core/point_cloud.hpp"
#include "litamin2/core/stamp.hpp"
#include "litamin2/dds/pointcloud2_conversion.hpp"
#include "litamin2_zero_copy/msg/PlainScan.h"

namespace litamin2::dds {

/// Points a PlainScan holds at most (the IDL's array size).
constexpr std::size_t kPlainScanCapacity = 131072;

/// Converts and validates a PlainScan into `out` (reusing its capacity); returns the error:
///  - kBadStamp: stamp.nanosec >= 1e9;
///  - kBadFrameId: no NUL within frame_id;
///  - kTooManyPoints: point_count > kPlainScanCapacity, or > options.max_points (when not 0);
///  - kBadTimeField: has_times other than 0 or 1; with options.read_time and has_times 1, a
///    kept point's time is not finite or beyond +-kMaxPointTime of the stamp;
///  - points with a NaN/Inf coordinate are dropped and counted in out.non_finite;
///  - with options.read_time and has_times 1: out.cloud.times gets the kept points' times and
///    out.time_field is "time"; without read_time (or has_times 0) the times are ignored.
/// PlainScan has no intensity: out.cloud.intensities stays empty.
CloudError from_plain_scan(const litamin2_zero_copy::msg::PlainScan& scan,
                           const CloudConversionOptions& options, CloudConversion& out);

/// Writes `cloud` into `scan` (e.g. a loaned sample): stamp, frame_id, point_count, the points
/// and, when the cloud has times, has_times 1 and the times (else 0 and time 0). Throws
/// std::invalid_argument for a cloud above kPlainScanCapacity points, a frame_id of 64 bytes
/// or more, or invalid times (point_times_error). Writes only points[0 .. size).
void to_plain_scan(const PointCloud& cloud, Stamp stamp, const std::string& frame_id,
                   litamin2_zero_copy::msg::PlainScan& scan);

}  // namespace litamin2::dds

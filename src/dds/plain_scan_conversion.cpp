#include "litamin2/dds/plain_scan_conversion.hpp"

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "litamin2/dds/time_conversion.hpp"

namespace litamin2::dds {

namespace {

static_assert(
    std::tuple_size<std::remove_reference_t<
            decltype(std::declval<litamin2_zero_copy::msg::PlainScan&>().points())>>::value ==
        kPlainScanCapacity,
    "kPlainScanCapacity is the IDL's array size");

}  // namespace

CloudError from_plain_scan(const litamin2_zero_copy::msg::PlainScan& scan,
                           const CloudConversionOptions& options, CloudConversion& out) {
  out.error = CloudError::kNone;
  out.message.clear();
  out.cloud.points.clear();
  out.cloud.intensities.clear();
  out.cloud.times.clear();
  out.time_field.clear();
  out.absolute_time = false;
  out.non_finite = 0;
  const std::uint32_t count = scan.point_count();
  out.total_points = count;
  if (scan.stamp().nanosec() >= 1'000'000'000u)
    return out.reject(CloudError::kBadStamp,
                      "stamp nanosec " + std::to_string(scan.stamp().nanosec()) + " >= 1e9");
  const auto& frame = scan.frame_id();
  if (std::memchr(frame.data(), '\0', frame.size()) == nullptr)
    return out.reject(CloudError::kBadFrameId,
                      "frame_id has no NUL within its " + std::to_string(frame.size()) + " bytes");
  if (count > kPlainScanCapacity)
    return out.reject(CloudError::kTooManyPoints, "point_count " + std::to_string(count) +
                                                      " > capacity " +
                                                      std::to_string(kPlainScanCapacity));
  if (options.max_points > 0 && count > options.max_points)
    return out.reject(CloudError::kTooManyPoints, std::to_string(count) + " points > limit " +
                                                      std::to_string(options.max_points));
  if (scan.has_times() > 1)
    return out.reject(CloudError::kBadTimeField,
                      "has_times is " + std::to_string(scan.has_times()) + " (0 or 1)");
  const bool with_times = options.read_time && scan.has_times() == 1;
  if (with_times) out.time_field = "time";
  auto& points = out.cloud.points;
  auto& times = out.cloud.times;
  points.resize(count);
  if (with_times) times.resize(count);
  std::size_t kept = 0;
  const auto& in = scan.points();
  for (std::uint32_t i = 0; i < count; ++i) {
    const litamin2_zero_copy::msg::PlainPoint& p = in[i];
    const float x = p.x(), y = p.y(), z = p.z();
    // x - x is 0 for finite x and NaN for NaN or +-Inf: one test for all three.
    if (!((x - x) + (y - y) + (z - z) == 0.0f)) {
      ++out.non_finite;
      continue;
    }
    if (with_times) {
      const float t = p.time();
      if (!std::isfinite(t) || std::abs(static_cast<double>(t)) > kMaxPointTime)
        return out.reject(CloudError::kBadTimeField,
                          "point " + std::to_string(i) + " has time " + std::to_string(t) +
                              " s (must be finite and within +-1 s of the stamp)");
      times[kept] = t;
    }
    points[kept++] = Eigen::Vector3f(x, y, z);
  }
  points.resize(kept);
  if (with_times) times.resize(kept);
  return CloudError::kNone;
}

void to_plain_scan(const PointCloud& cloud, Stamp stamp, const std::string& frame_id,
                   litamin2_zero_copy::msg::PlainScan& scan) {
  if (cloud.size() > kPlainScanCapacity)
    throw std::invalid_argument("to_plain_scan: " + std::to_string(cloud.size()) +
                                " points > capacity " + std::to_string(kPlainScanCapacity));
  auto& frame = scan.frame_id();
  if (frame_id.size() >= frame.size())
    throw std::invalid_argument("to_plain_scan: frame_id '" + frame_id + "' has " +
                                std::to_string(frame_id.size()) + " bytes (at most " +
                                std::to_string(frame.size() - 1) + ")");
  if (const auto why = point_times_error(cloud))
    throw std::invalid_argument("to_plain_scan: " + *why);
  scan.stamp(to_time(stamp));
  frame.fill('\0');
  std::memcpy(frame.data(), frame_id.data(), frame_id.size());
  const bool with_times = cloud.has_times();
  scan.point_count(static_cast<std::uint32_t>(cloud.size()));
  scan.has_times(with_times ? 1u : 0u);
  auto& out = scan.points();
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3f& v = cloud.points[i];
    out[i].x(v.x());
    out[i].y(v.y());
    out[i].z(v.z());
    out[i].time(with_times ? cloud.times[i] : 0.0f);
  }
}

}  // namespace litamin2::dds

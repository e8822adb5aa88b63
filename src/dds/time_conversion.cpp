#include "litamin2/dds/time_conversion.hpp"

#include <cmath>
#include <cstdint>
#include <limits>

namespace litamin2::dds {

double to_seconds(const builtin_interfaces::msg::Time& time) {
  return static_cast<double>(time.sec()) + static_cast<double>(time.nanosec()) * 1e-9;
}

builtin_interfaces::msg::Time to_time(double seconds) {
  builtin_interfaces::msg::Time time;
  if (!std::isfinite(seconds)) return time;
  constexpr double kMin = static_cast<double>(std::numeric_limits<std::int32_t>::min());
  constexpr double kMax = static_cast<double>(std::numeric_limits<std::int32_t>::max());
  if (seconds <= kMin) {
    time.sec(std::numeric_limits<std::int32_t>::min());
    return time;
  }
  if (seconds >= kMax + 1.0) {
    time.sec(std::numeric_limits<std::int32_t>::max());
    time.nanosec(999'999'999u);
    return time;
  }
  double whole = std::floor(seconds);
  auto nanos = static_cast<std::int64_t>(std::llround((seconds - whole) * 1e9));
  if (nanos >= 1'000'000'000) {
    nanos -= 1'000'000'000;
    whole += 1.0;
  }
  if (whole > kMax) {
    time.sec(std::numeric_limits<std::int32_t>::max());
    time.nanosec(999'999'999u);
    return time;
  }
  time.sec(static_cast<std::int32_t>(whole));
  time.nanosec(static_cast<std::uint32_t>(nanos));
  return time;
}

}  // namespace litamin2::dds

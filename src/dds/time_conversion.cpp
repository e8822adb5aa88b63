#include "litamin2/dds/time_conversion.hpp"

#include <chrono>
#include <cstdint>
#include <limits>

namespace litamin2::dds {
namespace {

constexpr std::int64_t kNsPerSecond = 1'000'000'000;

}  // namespace

Stamp to_stamp(const builtin_interfaces::msg::Time& time) {
  return Stamp{static_cast<std::int64_t>(time.sec()) * kNsPerSecond +
               static_cast<std::int64_t>(time.nanosec())};
}

builtin_interfaces::msg::Time to_time(Stamp stamp) {
  builtin_interfaces::msg::Time time;
  std::int64_t sec = stamp.nanoseconds / kNsPerSecond;
  std::int64_t nanosec = stamp.nanoseconds % kNsPerSecond;
  if (nanosec < 0) {
    nanosec += kNsPerSecond;
    --sec;
  }
  constexpr std::int64_t kMin = std::numeric_limits<std::int32_t>::min();
  constexpr std::int64_t kMax = std::numeric_limits<std::int32_t>::max();
  if (sec < kMin) {
    sec = kMin;
    nanosec = 0;
  } else if (sec > kMax) {
    sec = kMax;
    nanosec = kNsPerSecond - 1;
  }
  time.sec(static_cast<std::int32_t>(sec));
  time.nanosec(static_cast<std::uint32_t>(nanosec));
  return time;
}

Stamp wall_clock_now() {
  return Stamp{std::chrono::duration_cast<std::chrono::nanoseconds>(
                   std::chrono::system_clock::now().time_since_epoch())
                   .count()};
}

}  // namespace litamin2::dds

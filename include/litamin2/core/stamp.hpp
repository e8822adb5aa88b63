#pragma once
/// The one representation of time along a scan's path: nanoseconds since the Unix epoch, as a
/// ROS 2 header stamp carries it (builtin_interfaces/Time converts to and from it exactly,
/// dds/time_conversion.hpp). Point clouds, odometry, keyframes and the store all use it.

#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace litamin2 {

struct Stamp {
  /// Nanoseconds since 1970-01-01 00:00:00 UTC.
  std::int64_t nanoseconds = 0;

  /// The stamp nearest to `seconds` since the epoch; throws std::invalid_argument for a value
  /// that is not finite or beyond +-292 years (outside int64 nanoseconds).
  static Stamp from_seconds(double seconds) {
    if (!(std::abs(seconds) < 9.2e9))
      throw std::invalid_argument("time stamp out of range (seconds since the epoch)");
    return Stamp{static_cast<std::int64_t>(std::llround(seconds * 1e9))};
  }
  /// Seconds since the epoch (exact to about 0.2 microseconds today).
  double seconds() const { return static_cast<double>(nanoseconds) * 1e-9; }

  friend bool operator==(Stamp a, Stamp b) { return a.nanoseconds == b.nanoseconds; }
  friend bool operator!=(Stamp a, Stamp b) { return a.nanoseconds != b.nanoseconds; }
  friend bool operator<(Stamp a, Stamp b) { return a.nanoseconds < b.nanoseconds; }
};

}  // namespace litamin2

#pragma once
/// ROS 2 builtin_interfaces/Time <-> seconds as double.

#include "builtin_interfaces/msg/Time.h"

namespace litamin2::dds {

/// sec + nanosec * 1e-9.
double to_seconds(const builtin_interfaces::msg::Time& time);
/// Splits seconds into (sec, nanosec) with nanosec in [0, 1e9), rounding to the nearest
/// nanosecond (so negative times have a negative sec and a positive nanosec, as in ROS 2).
/// Non-finite input gives time 0; values outside int32 seconds are clamped.
builtin_interfaces::msg::Time to_time(double seconds);

}  // namespace litamin2::dds

#pragma once
/// ROS 2 builtin_interfaces/Time <-> Stamp (nanoseconds since the epoch).

#include "builtin_interfaces/msg/Time.h"
#include "litamin2/core/stamp.hpp"

namespace litamin2::dds {

/// sec * 1e9 + nanosec, exactly (nanosec is not checked to be below 1e9 here; the message
/// conversions that read stamps reject it).
Stamp to_stamp(const builtin_interfaces::msg::Time& time);
/// (sec, nanosec) with nanosec in [0, 1e9): negative stamps have a negative sec and a positive
/// nanosec, as in ROS 2. Stamps beyond int32 seconds (before 1901-12-13, after 2038-01-19)
/// are clamped to its range.
builtin_interfaces::msg::Time to_time(Stamp stamp);
/// The wall clock now (stamps of published status and summaries).
Stamp wall_clock_now();

}  // namespace litamin2::dds

// Stamps: seconds <-> nanoseconds, and ROS 2 builtin_interfaces/Time <-> Stamp, exactly.

#include "litamin2/dds/time_conversion.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

namespace litamin2::dds {
namespace {

builtin_interfaces::msg::Time ros_time(std::int32_t sec, std::uint32_t nanosec) {
  builtin_interfaces::msg::Time t;
  t.sec(sec);
  t.nanosec(nanosec);
  return t;
}

TEST(Stamp, FromSecondsRoundsToTheNearestNanosecond) {
  EXPECT_EQ(Stamp::from_seconds(1.5).nanoseconds, 1'500'000'000);
  EXPECT_EQ(Stamp::from_seconds(-0.25).nanoseconds, -250'000'000);
  EXPECT_EQ(Stamp::from_seconds(2.9999999999).nanoseconds, 3'000'000'000);
  EXPECT_EQ(Stamp::from_seconds(1.5).seconds(), 1.5);
  EXPECT_THROW(Stamp::from_seconds(std::nan("")), std::invalid_argument);
  EXPECT_THROW(Stamp::from_seconds(1e20), std::invalid_argument);
  EXPECT_THROW(Stamp::from_seconds(-std::numeric_limits<double>::infinity()),
               std::invalid_argument);
  EXPECT_TRUE(Stamp{1} < Stamp{2});
  EXPECT_FALSE(Stamp{2} < Stamp{2});
  EXPECT_EQ(Stamp{7}, Stamp{7});
}

TEST(TimeConversion, RosTimeRoundTripsExactly) {
  for (const auto& [sec, nanosec] : {std::pair<std::int32_t, std::uint32_t>{0, 0},
                                     {10, 1},
                                     {1'700'000'000, 123'456'789},
                                     {-1, 999'999'999},
                                     {std::numeric_limits<std::int32_t>::max(), 999'999'999},
                                     {std::numeric_limits<std::int32_t>::min(), 0}}) {
    const Stamp stamp = to_stamp(ros_time(sec, nanosec));
    EXPECT_EQ(stamp.nanoseconds, static_cast<std::int64_t>(sec) * 1'000'000'000 + nanosec);
    const auto back = to_time(stamp);
    EXPECT_EQ(back.sec(), sec);
    EXPECT_EQ(back.nanosec(), nanosec);
  }
}

TEST(TimeConversion, NegativeStampsHaveAPositiveNanosec) {
  const auto t = to_time(Stamp{-1});
  EXPECT_EQ(t.sec(), -1);
  EXPECT_EQ(t.nanosec(), 999'999'999u);
  EXPECT_EQ(to_time(Stamp::from_seconds(-0.25)).sec(), -1);
  EXPECT_EQ(to_time(Stamp::from_seconds(-0.25)).nanosec(), 750'000'000u);
}

TEST(TimeConversion, StampsBeyondInt32SecondsAreClamped) {
  const auto late = to_time(Stamp{std::numeric_limits<std::int64_t>::max()});
  EXPECT_EQ(late.sec(), std::numeric_limits<std::int32_t>::max());
  EXPECT_EQ(late.nanosec(), 999'999'999u);
  const auto early = to_time(Stamp{std::numeric_limits<std::int64_t>::min()});
  EXPECT_EQ(early.sec(), std::numeric_limits<std::int32_t>::min());
  EXPECT_EQ(early.nanosec(), 0u);
}

TEST(TimeConversion, WallClockIsNow) {
  // After 2026-01-01 and before 2100: a wall clock, not a monotonic one.
  const double now = wall_clock_now().seconds();
  EXPECT_GT(now, 1'767'225'600.0);
  EXPECT_LT(now, 4'102'444'800.0);
}

}  // namespace
}  // namespace litamin2::dds

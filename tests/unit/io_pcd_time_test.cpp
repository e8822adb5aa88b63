// Per-point time fields of PCD scans (read_pcd): each driver's name and type, relative and
// absolute times, invalid times rejected.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "litamin2/io/io_error.hpp"
#include "litamin2/io/pcd.hpp"
#include "support/io_test_support.hpp"

namespace litamin2::io {
namespace {

namespace fs = std::filesystem;
using litamin2::testing::temp_dir;

PointCloud cloud(std::size_t n) {
  PointCloud c;
  for (std::size_t i = 0; i < n; ++i)
    c.points.emplace_back(0.5f * static_cast<float>(i), 1.0f,
                          -1.5f + 0.01f * static_cast<float>(i));
  return c;
}

/// Seconds from the sweep start of point i of n.
double sweep_time(std::size_t i, std::size_t n) {
  return 0.1 * static_cast<double>(i) / n;
}

/// Writes `n` points with one time field and reads them back.
PointCloud round_trip(const std::string& name, char type, std::size_t size, double unit,
                      double origin, std::size_t n = 200) {
  PcdField f{name, type, size, {}};
  for (std::size_t i = 0; i < n; ++i) f.values.push_back((origin + sweep_time(i, n)) / unit);
  const fs::path file = temp_dir() / (name + "_" + type + std::to_string(size) + ".pcd");
  write_pcd_binary(file.string(), cloud(n), {f});
  return read_pcd(file.string());
}

TEST(IoPcdTime, EachDriversFieldAsRelativeSeconds) {
  struct Case {
    const char* name;
    char type;
    std::size_t size;
    double unit;
  };
  // Ouster t (U 4, ns), Velodyne time (F 4, s), Hesai timestamp (F 8, s), Livox offset_time
  // (U 4, ns).
  for (const Case& c : {Case{"t", 'U', 4, 1e-9}, Case{"time", 'F', 4, 1.0},
                        Case{"timestamp", 'F', 8, 1.0}, Case{"offset_time", 'U', 4, 1e-9}}) {
    const PointCloud read = round_trip(c.name, c.type, c.size, c.unit, 0.0);
    ASSERT_EQ(read.times.size(), 200u) << c.name;
    for (std::size_t i = 0; i < read.size(); ++i)
      ASSERT_NEAR(read.times[i], sweep_time(i, 200), 1e-8) << c.name << " " << i;
  }
}

TEST(IoPcdTime, AbsoluteTimesAreTakenFromTheSweepStart) {
  // Hesai's absolute epoch seconds (F 8).
  const PointCloud c = round_trip("timestamp", 'F', 8, 1.0, 1733097600.25);
  ASSERT_EQ(c.times.size(), 200u);
  EXPECT_EQ(c.times.front(), 0.0f);
  for (std::size_t i = 0; i < c.size(); ++i) ASSERT_NEAR(c.times[i], sweep_time(i, 200), 1e-6) << i;
}

TEST(IoPcdTime, FilesWithoutATimeFieldHaveNoTimes) {
  const fs::path file = temp_dir() / "no_time.pcd";
  write_pcd_binary(file.string(), cloud(10),
                   {PcdField{"ring", 'U', 2, std::vector<double>(10, 3)}});
  EXPECT_TRUE(read_pcd(file.string()).times.empty());
}

TEST(IoPcdTime, InvalidTimesAreRejected) {
  const fs::path file = temp_dir() / "bad_time.pcd";
  PcdField nan{"time", 'F', 4, std::vector<double>(10, 0.01)};
  nan.values[4] = std::numeric_limits<double>::quiet_NaN();
  write_pcd_binary(file.string(), cloud(10), {nan});
  EXPECT_THROW(read_pcd(file.string()), IoError);
  // Absolute seconds in float32 cannot resolve a sweep.
  write_pcd_binary(file.string(), cloud(10),
                   {PcdField{"time", 'F', 4, std::vector<double>(10, 1733097600.0)}});
  EXPECT_THROW(read_pcd(file.string()), IoError);
  // Times spanning 3 s are not one sweep.
  PcdField span{"timestamp", 'F', 8, std::vector<double>(10, 1733097600.0)};
  span.values[9] += 3.0;
  write_pcd_binary(file.string(), cloud(10), {span});
  try {
    read_pcd(file.string());
    FAIL() << "a 3 s span was accepted";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("bad_time.pcd"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace litamin2::io

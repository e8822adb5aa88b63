#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "litamin2/io/io_error.hpp"
#include "litamin2/io/kitti_bin.hpp"
#include "support/io_test_support.hpp"

namespace fs = std::filesystem;
using litamin2::PointCloud;
using namespace litamin2::io;

namespace {

using litamin2::testing::expect_io_error;
using litamin2::testing::temp_dir;
using litamin2::testing::write_text;

void write_floats(const fs::path& path, const std::vector<float>& values) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(values.data()),
            static_cast<std::streamsize>(values.size() * sizeof(float)));
}

void write_bytes(const fs::path& path, std::size_t n) {
  std::ofstream out(path, std::ios::binary);
  const std::string zeros(n, '\0');
  out.write(zeros.data(), static_cast<std::streamsize>(n));
}

/// Points along a scan line at ~10 m, as a real scan stores them (consecutive points close).
PointCloud scan_line(std::size_t n, bool with_intensity, float z = 0.5f) {
  PointCloud cloud;
  for (std::size_t i = 0; i < n; ++i) {
    const float a = 0.01f * static_cast<float>(i);
    cloud.points.emplace_back(10.0f * std::cos(a), 10.0f * std::sin(a), z);
    if (with_intensity) cloud.intensities.push_back(0.1f + 0.01f * static_cast<float>(i));
  }
  return cloud;
}

const std::string kShared = LITAMIN2_SHARED_DATA_DIR;

}  // namespace

TEST(IoKittiBin, RoundTripWithIntensity) {
  const fs::path file = temp_dir() / "scan.bin";
  const PointCloud cloud = scan_line(7, true);  // 112 bytes: multiple of 16 only
  write_kitti_bin(file.string(), cloud);
  EXPECT_EQ(fs::file_size(file), 7u * 16u);
  const PointCloud back = read_kitti_bin(file.string());
  ASSERT_EQ(back.size(), cloud.size());
  ASSERT_TRUE(back.has_intensities());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    EXPECT_EQ(back.points[i], cloud.points[i]);
    EXPECT_EQ(back.intensities[i], cloud.intensities[i]);
  }
}

TEST(IoKittiBin, WriteWithoutIntensityWritesZeros) {
  const fs::path file = temp_dir() / "scan.bin";
  const PointCloud cloud = scan_line(5, false);
  write_kitti_bin(file.string(), cloud);
  KittiBinOptions opt;
  opt.layout = KittiBinLayout::kXYZI;
  const PointCloud back = read_kitti_bin(file.string(), opt);
  ASSERT_EQ(back.size(), 5u);
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(back.points[i], cloud.points[i]);
    EXPECT_EQ(back.intensities[i], 0.0f);
  }
}

TEST(IoKittiBin, AutoDetectsXyzBySize) {
  const fs::path file = temp_dir() / "xyz.bin";
  write_floats(file, {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15});  // 60 bytes
  const PointCloud cloud = read_kitti_bin(file.string());
  ASSERT_EQ(cloud.size(), 5u);
  EXPECT_FALSE(cloud.has_intensities());
  EXPECT_EQ(cloud.points[4], Eigen::Vector3f(13, 14, 15));
}

TEST(IoKittiBin, AmbiguousSizeXyziWithPlausibleIntensities) {
  const fs::path file = temp_dir() / "xyzi48.bin";
  const PointCloud cloud = scan_line(12, true);  // 192 bytes = 4 * 48: both layouts fit
  write_kitti_bin(file.string(), cloud);
  const PointCloud back = read_kitti_bin(file.string());
  ASSERT_EQ(back.size(), 12u);
  EXPECT_TRUE(back.has_intensities());
  EXPECT_EQ(back.points[11], cloud.points[11]);
}

TEST(IoKittiBin, AmbiguousSizeXyzWithNegativeCoordinates) {
  const fs::path file = temp_dir() / "xyz48.bin";
  const PointCloud cloud = scan_line(16, false, -1.7f);  // 192 bytes
  std::vector<float> raw;
  for (const auto& p : cloud.points) raw.insert(raw.end(), {p.x(), p.y(), p.z()});
  write_floats(file, raw);
  const PointCloud back = read_kitti_bin(file.string());
  ASSERT_EQ(back.size(), 16u);
  EXPECT_FALSE(back.has_intensities());
  EXPECT_EQ(back.points[15], cloud.points[15]);
}

TEST(IoKittiBin, AmbiguousSizeXyzAllPositiveDecidedByContinuity) {
  // Every 4th float is a valid "intensity" here, so only the point continuity can decide.
  const fs::path file = temp_dir() / "xyzpos.bin";
  const PointCloud cloud = scan_line(16, false, 0.5f);
  std::vector<float> raw;
  for (const auto& p : cloud.points) raw.insert(raw.end(), {p.x(), p.y(), p.z()});
  write_floats(file, raw);
  const PointCloud back = read_kitti_bin(file.string());
  ASSERT_EQ(back.size(), 16u);
  EXPECT_FALSE(back.has_intensities());
}

TEST(IoKittiBin, DropsNonFinitePoints) {
  const fs::path file = temp_dir() / "nan.bin";
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  write_floats(file, {1, 2, 3, 0.5f, nan, 0, 0, 0.1f, 4, inf, 6, 0.2f, 7, 8, 9, 0.7f, 1, 1, 1, 1});
  const PointCloud cloud = read_kitti_bin(file.string());
  ASSERT_EQ(cloud.size(), 3u);
  ASSERT_EQ(cloud.intensities.size(), 3u);
  EXPECT_EQ(cloud.points[1], Eigen::Vector3f(7, 8, 9));
  EXPECT_EQ(cloud.intensities[1], 0.7f);
}

TEST(IoKittiBin, NonFiniteIntensityOfAFinitePointIsAnError) {
  // Regression (issue 14): it was passed on as NaN/Inf.
  const fs::path file = temp_dir() / "nan_i.bin";
  const float nan = std::numeric_limits<float>::quiet_NaN();
  write_floats(file, {1, 2, 3, 0.5f, 4, 5, 6, nan, 7, 8, 9, 0.7f, 1, 1, 1, 1});
  KittiBinOptions xyzi;
  xyzi.layout = KittiBinLayout::kXYZI;
  expect_io_error([&] { read_kitti_bin(file.string(), xyzi); }, "nan_i.bin", "point 1: intensity");
}

TEST(IoKittiBin, VerticalCorrectionBeyondFloatRangeIsAnError) {
  // Regression (issue 14): a point a hair below the float maximum became Inf.
  const fs::path file = temp_dir() / "edge.bin";
  const float big = std::numeric_limits<float>::max();
  write_floats(file, {1, 2, 3, 0.5f, big, 0, big, 0.2f, 7, 8, 9, 0.7f, 1, 1, 1, 1});
  KittiBinOptions options;
  options.layout = KittiBinLayout::kXYZI;
  options.vertical_angle_correction_deg = 0.205;
  expect_io_error([&] { read_kitti_bin(file.string(), options); }, "edge.bin",
                  "leaves the float range");
}

TEST(IoKittiBin, RealSharedScansAreDetectedAsXyz) {
  const std::string dir = kShared + "/kitti/seq00_frames_xyz";
  if (!fs::exists(dir + "/000000.bin") || !fs::exists(dir + "/000001.bin")) {
    GTEST_SKIP() << "shared KITTI scans not found under " << dir;
  }
  const PointCloud scan0 = read_kitti_bin(dir + "/000000.bin");  // size is a multiple of 48
  EXPECT_EQ(scan0.size(), 124668u);
  EXPECT_FALSE(scan0.has_intensities());
  EXPECT_NEAR(scan0.points[0].x(), 52.898f, 1e-3f);
  const PointCloud scan1 = read_kitti_bin(dir + "/000001.bin");
  EXPECT_EQ(scan1.size(), 124605u);
  EXPECT_FALSE(scan1.has_intensities());
  KittiBinOptions xyzi;
  xyzi.layout = KittiBinLayout::kXYZI;
  expect_io_error([&] { read_kitti_bin(dir + "/000001.bin", xyzi); }, "000001.bin",
                  "not a multiple of 16");
}

TEST(IoKittiBin, VerticalAngleCorrectionTiltsKeepingRange) {
  const double deg = 0.205;
  const double rad = deg * M_PI / 180.0;
  PointCloud cloud;
  cloud.points = {{10, 0, 0}, {6, 8, -1}, {0, 0, 5}, {-3, 4, 2}};
  PointCloud corrected = cloud;
  apply_vertical_angle_correction(corrected, deg);
  // (10,0,0) is tilted straight up by 10 * angle.
  EXPECT_NEAR(corrected.points[0].z(), 10.0 * std::sin(rad), 1e-5);
  EXPECT_NEAR(corrected.points[0].y(), 0.0, 1e-6);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const double r = cloud.points[i].norm();
    EXPECT_NEAR(corrected.points[i].norm(), r, 1e-5) << i;
    if (i == 2) continue;  // on the z axis: unchanged
    EXPECT_NEAR((corrected.points[i] - cloud.points[i]).norm(), r * rad, 1e-5 * r) << i;
    EXPECT_GT(corrected.points[i].z(), cloud.points[i].z()) << i;
    // Azimuth unchanged.
    EXPECT_NEAR(std::atan2(corrected.points[i].y(), corrected.points[i].x()),
                std::atan2(cloud.points[i].y(), cloud.points[i].x()), 1e-6);
  }
  EXPECT_EQ(corrected.points[2], cloud.points[2]);

  // Through the reader option.
  const fs::path file = temp_dir() / "c.bin";
  write_kitti_bin(file.string(), cloud);
  KittiBinOptions opt;
  opt.vertical_angle_correction_deg = deg;
  const PointCloud read = read_kitti_bin(file.string(), opt);
  ASSERT_EQ(read.size(), cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    EXPECT_NEAR((read.points[i] - corrected.points[i]).norm(), 0.0, 1e-6);
  }
  // Default: untouched.
  EXPECT_EQ(read_kitti_bin(file.string()).points[0], cloud.points[0]);
}

TEST(IoKittiBin, ErrorsNameTheFile) {
  const fs::path dir = temp_dir();
  write_bytes(dir / "scan_1001.bin", 1001);
  expect_io_error([&] { read_kitti_bin((dir / "scan_1001.bin").string()); }, "scan_1001.bin",
                  "1001");
  write_bytes(dir / "empty_scan.bin", 0);
  expect_io_error([&] { read_kitti_bin((dir / "empty_scan.bin").string()); }, "empty_scan.bin");
  expect_io_error([&] { read_kitti_bin((dir / "missing_scan.bin").string()); }, "missing_scan.bin",
                  "does not exist");
  expect_io_error([&] { read_kitti_bin(dir.string()); }, dir.filename().string(), "directory");
  // 60 bytes forced as XYZI: truncated.
  write_bytes(dir / "short.bin", 60);
  KittiBinOptions xyzi;
  xyzi.layout = KittiBinLayout::kXYZI;
  expect_io_error([&] { read_kitti_bin((dir / "short.bin").string(), xyzi); }, "short.bin");
  // Unwritable destination.
  expect_io_error([&] { write_kitti_bin((dir / "no_dir" / "x.bin").string(), scan_line(2, true)); },
                  "x.bin");
}

TEST(IoKittiBin, WriterRejectsMismatchedIntensities) {
  PointCloud cloud = scan_line(3, true);
  cloud.intensities.pop_back();
  EXPECT_THROW(write_kitti_bin((temp_dir() / "bad.bin").string(), cloud), std::invalid_argument);
}

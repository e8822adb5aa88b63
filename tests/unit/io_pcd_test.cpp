#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "litamin2/io/io_error.hpp"
#include "litamin2/io/pcd.hpp"
#include "support/io_test_support.hpp"

#include <liblzf/lzf.h>

namespace fs = std::filesystem;
using litamin2::PointCloud;
using namespace litamin2::io;

namespace {

using litamin2::testing::expect_io_error;
using litamin2::testing::temp_dir;
using litamin2::testing::write_text;

template <typename T>
void put(std::string& out, T value) {
  char buf[sizeof(T)];
  std::memcpy(buf, &value, sizeof(T));
  out.append(buf, sizeof(T));
}

PointCloud sample(bool with_intensity) {
  PointCloud cloud;
  for (int i = 0; i < 20; ++i) {
    cloud.points.emplace_back(0.5f * i, -1.25f * i, 3.0f + 0.001f * i);
    if (with_intensity) cloud.intensities.push_back(0.01f * i);
  }
  return cloud;
}

/// A DATA binary_compressed file as PCL writes it: the header, the compressed and uncompressed
/// sizes, then `soa` (the points' bytes field by field) compressed with LZF.
std::string compressed_pcd(const std::string& header, const std::string& soa) {
  std::string packed(soa.size() + 64, '\0');
  const unsigned int size = lzf_compress(soa.data(), static_cast<unsigned int>(soa.size()),
                                         packed.data(), static_cast<unsigned int>(packed.size()));
  if (size == 0) throw std::runtime_error("lzf_compress failed");
  std::string out = header;
  put<std::uint32_t>(out, size);
  put<std::uint32_t>(out, static_cast<std::uint32_t>(soa.size()));
  out.append(packed.data(), size);
  return out;
}

const std::string kHeader3 =
    "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n";

}  // namespace

TEST(IoPcd, BinaryRoundTripWithAndWithoutIntensity) {
  const fs::path dir = temp_dir();
  for (bool with_i : {true, false}) {
    const fs::path file = dir / (with_i ? "i.pcd" : "noi.pcd");
    const PointCloud cloud = sample(with_i);
    write_pcd_binary(file.string(), cloud);
    const PointCloud back = read_pcd(file.string());
    ASSERT_EQ(back.size(), cloud.size());
    EXPECT_EQ(back.has_intensities(), with_i);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      EXPECT_EQ(back.points[i], cloud.points[i]);
      if (with_i) {
        EXPECT_EQ(back.intensities[i], cloud.intensities[i]);
      }
    }
  }
}

TEST(IoPcd, EmptyCloudRoundTrip) {
  const fs::path file = temp_dir() / "empty_cloud.pcd";
  write_pcd_binary(file.string(), PointCloud{});
  EXPECT_TRUE(read_pcd(file.string()).empty());
}

TEST(IoPcd, AsciiWithExtraAndMultiCountFields) {
  const fs::path file = temp_dir() / "ascii.pcd";
  write_text(file,
             "# .PCD v0.7 - Point Cloud Data file format\r\n"
             "VERSION 0.7\r\n"
             "FIELDS hist x y z rgb intensity\r\n"
             "SIZE 4 4 4 4 4 2\r\n"
             "TYPE F F F F U U\r\n"
             "COUNT 3 1 1 1 1 1\r\n"
             "WIDTH 2\r\nHEIGHT 2\r\nVIEWPOINT 0 0 0 1 0 0 0\r\nPOINTS 4\r\nDATA ascii\r\n"
             "9 9 9 1.5 2.5 3.5 4278190080 100\r\n"
             "9 9 9 nan nan nan 0 0\r\n"
             "9 9 9 -1 -2 -3 0 65535\r\n"
             "9 9 9 4e1 5 6 0 7\r\n");
  const PointCloud cloud = read_pcd(file.string());
  ASSERT_EQ(cloud.size(), 3u);  // the NaN point is dropped
  ASSERT_EQ(cloud.intensities.size(), 3u);
  EXPECT_EQ(cloud.points[0], Eigen::Vector3f(1.5f, 2.5f, 3.5f));
  EXPECT_EQ(cloud.points[1], Eigen::Vector3f(-1, -2, -3));
  EXPECT_EQ(cloud.points[2], Eigen::Vector3f(40, 5, 6));
  EXPECT_EQ(cloud.intensities[0], 100.0f);
  EXPECT_EQ(cloud.intensities[1], 65535.0f);
}

TEST(IoPcd, BinaryDoubleXyzU8IntensityAndSkippedFields) {
  const fs::path file = temp_dir() / "bin.pcd";
  std::string data =
      "VERSION .7\nFIELDS normal x y z _ intensity\nSIZE 4 8 8 8 1 1\nTYPE F F F F U U\n"
      "COUNT 3 1 1 1 5 1\nWIDTH 3\nHEIGHT 1\nPOINTS 3\nDATA binary\n";
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k) put<float>(data, -7.0f);
    put<double>(data, 1.0 + i);
    put<double>(data, 10.0 + i);
    put<double>(data, 100.0 + i);
    for (int k = 0; k < 5; ++k) put<std::uint8_t>(data, 0xAB);
    put<std::uint8_t>(data, static_cast<std::uint8_t>(200 + i));
  }
  write_text(file, data);
  const PointCloud cloud = read_pcd(file.string());
  ASSERT_EQ(cloud.size(), 3u);
  EXPECT_EQ(cloud.points[2], Eigen::Vector3f(3, 12, 102));
  EXPECT_EQ(cloud.intensities[2], 202.0f);
}

TEST(IoPcd, ErrorsNameTheFile) {
  const fs::path dir = temp_dir();
  auto check = [&](const std::string& name, const std::string& content, const std::string& also) {
    write_text(dir / name, content);
    expect_io_error([&] { read_pcd((dir / name).string()); }, name, also);
  };
  check("unknown_data.pcd", kHeader3 + "WIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA binary_zstd\n",
        "unknown DATA type");
  check("mismatch.pcd", kHeader3 + "WIDTH 3\nHEIGHT 2\nPOINTS 5\nDATA ascii\n", "POINTS");
  std::string truncated = kHeader3 + "WIDTH 3\nHEIGHT 1\nPOINTS 3\nDATA binary\n";
  for (int i = 0; i < 8; ++i) put<float>(truncated, 1.0f);  // 8 of 9 floats
  check("truncated_bin.pcd", truncated, "truncated");
  check("truncated_ascii.pcd", kHeader3 + "WIDTH 3\nHEIGHT 1\nPOINTS 3\nDATA ascii\n1 2 3\n4 5 6\n",
        "truncated");
  check("short_line.pcd", kHeader3 + "WIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA ascii\n1 2\n", "line 11");
  check("bad_number.pcd", kHeader3 + "WIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA ascii\n1 2 zz\n", "zz");
  check("no_z.pcd",
        "FIELDS x y\nSIZE 4 4\nTYPE F F\nCOUNT 1 1\nWIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA ascii\n1 2\n",
        "'z'");
  check("int_xyz.pcd",
        "FIELDS x y z\nSIZE 4 4 4\nTYPE I I I\nWIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA ascii\n1 2 3\n",
        "TYPE");
  check("size_mismatch.pcd", "FIELDS x y z\nSIZE 4 4\nTYPE F F F\nWIDTH 1\nDATA ascii\n1 2 3\n",
        "SIZE");
  check("empty.pcd", "", "DATA");
  // Regressions (issue 14): a finite point's intensity must be a finite float, and coordinates
  // must fit in a float (they were dropped silently).
  const std::string with_i =
      "FIELDS x y z intensity\nSIZE 4 4 4 4\nTYPE F F F F\nWIDTH 2\nHEIGHT 1\nPOINTS 2\nDATA "
      "ascii\n";
  check("nan_intensity.pcd", with_i + "1 2 3 4\n1 2 3 nan\n", "point 1: intensity");
  check("inf_intensity.pcd", with_i + "1 2 3 inf\n1 2 3 4\n", "point 0: intensity");
  check("huge.pcd", kHeader3 + "WIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA ascii\n1e300 2 3\n",
        "beyond float range");
  check("garbage.pcd", std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16), "garbage.pcd");
  expect_io_error([&] { read_pcd((dir / "missing.pcd").string()); }, "missing.pcd");
  expect_io_error([&] { write_pcd_binary((dir / "nodir" / "out.pcd").string(), sample(false)); },
                  "out.pcd");
}

TEST(IoPcd, BinaryWithExtraFieldsRoundTripsAndIsValidated) {
  const fs::path dir = temp_dir();
  const std::string path = (dir / "t.pcd").string();
  const PointCloud cloud = sample(true);
  std::vector<double> t, ring;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    t.push_back(0.005 * i);
    ring.push_back(static_cast<double>(i % 16));
  }
  write_pcd_binary(path, cloud, {{"t", 'F', 4, t}, {"ring", 'U', 2, ring}});
  const PointCloud back = read_pcd(path);  // the extra fields are skipped by the reader
  ASSERT_EQ(back.size(), cloud.size());
  EXPECT_EQ(back.points[7], cloud.points[7]);
  EXPECT_EQ(back.intensities[7], cloud.intensities[7]);
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(bytes.find("FIELDS x y z intensity t ring\nSIZE 4 4 4 4 4 2\nTYPE F F F F F U\n"),
            std::string::npos);
  const std::size_t data = bytes.find("DATA binary\n") + 12;
  float t7;
  std::uint16_t ring7;
  std::memcpy(&t7, bytes.data() + data + 7 * 22 + 16, 4);
  std::memcpy(&ring7, bytes.data() + data + 7 * 22 + 20, 2);
  EXPECT_FLOAT_EQ(t7, 0.035f);
  EXPECT_EQ(ring7, 7);
  // Without extra fields the file is the plain writer's.
  write_pcd_binary(path, cloud, {});
  const std::string plain = (dir / "p.pcd").string();
  write_pcd_binary(plain, cloud);
  std::ifstream a(path, std::ios::binary), b(plain, std::ios::binary);
  EXPECT_EQ(std::string((std::istreambuf_iterator<char>(a)), std::istreambuf_iterator<char>()),
            std::string((std::istreambuf_iterator<char>(b)), std::istreambuf_iterator<char>()));

  EXPECT_THROW(write_pcd_binary(path, cloud, {{"t", 'F', 4, {1.0}}}), std::invalid_argument);
  EXPECT_THROW(write_pcd_binary(path, cloud, {{"x", 'F', 4, t}}), std::invalid_argument);
  EXPECT_THROW(write_pcd_binary(path, cloud, {{"t", 'F', 2, t}}), std::invalid_argument);
  EXPECT_THROW(write_pcd_binary(path, cloud, {{"my t", 'F', 4, t}}), std::invalid_argument);
  EXPECT_THROW(write_pcd_binary(path, cloud, {{"t", 'F', 4, t}, {"t", 'U', 2, ring}}),
               std::invalid_argument);
}

TEST(IoPcd, BinaryCompressedIsReadFieldByField) {
  // x y z intensity as float32 and t as uint32 nanoseconds, 50 points, one of them a NaN point;
  // the data are laid out field by field, as PCL writes binary_compressed.
  constexpr int kPoints = 50;
  std::string soa;
  for (int axis = 0; axis < 3; ++axis) {
    for (int i = 0; i < kPoints; ++i) {
      const float v = i == 7 ? std::nanf("") : 0.25f * i + 100.0f * axis;
      put<float>(soa, v);
    }
  }
  for (int i = 0; i < kPoints; ++i) put<float>(soa, 2.0f * i);
  for (int i = 0; i < kPoints; ++i) put<std::uint32_t>(soa, 1000u * i);
  const std::string header =
      "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z intensity t\nSIZE 4 4 4 4 4\nTYPE F F F F U\n"
      "COUNT 1 1 1 1 1\nWIDTH 50\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 50\n"
      "DATA binary_compressed\n";
  const fs::path file = temp_dir() / "compressed.pcd";
  write_text(file, compressed_pcd(header, soa));
  const PointCloud cloud = read_pcd(file.string());
  ASSERT_EQ(cloud.size(), static_cast<std::size_t>(kPoints - 1));  // the NaN point is dropped
  ASSERT_EQ(cloud.intensities.size(), cloud.size());
  ASSERT_EQ(cloud.times.size(), cloud.size());
  for (std::size_t k = 0; k < cloud.size(); ++k) {
    const int i = static_cast<int>(k < 7 ? k : k + 1);
    EXPECT_EQ(cloud.points[k], Eigen::Vector3f(0.25f * i, 0.25f * i + 100.0f, 0.25f * i + 200.0f));
    EXPECT_EQ(cloud.intensities[k], 2.0f * i);
    EXPECT_FLOAT_EQ(cloud.times[k], 1e-6f * i);
  }
}

TEST(IoPcd, BinaryCompressedEqualsBinary) {
  const fs::path dir = temp_dir();
  const PointCloud cloud = sample(true);
  write_pcd_binary((dir / "plain.pcd").string(), cloud);
  std::string soa;
  for (int axis = 0; axis < 3; ++axis)
    for (const auto& p : cloud.points) put<float>(soa, p[axis]);
  for (float v : cloud.intensities) put<float>(soa, v);
  const std::string header =
      "VERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\n"
      "WIDTH 20\nHEIGHT 1\nPOINTS 20\nDATA binary_compressed\n";
  write_text(dir / "packed.pcd", compressed_pcd(header, soa));
  const PointCloud plain = read_pcd((dir / "plain.pcd").string());
  const PointCloud packed = read_pcd((dir / "packed.pcd").string());
  EXPECT_EQ(plain.points, packed.points);
  EXPECT_EQ(plain.intensities, packed.intensities);
}

TEST(IoPcd, BinaryCompressedErrors) {
  const fs::path dir = temp_dir();
  const std::string header = kHeader3 + "WIDTH 4\nHEIGHT 1\nPOINTS 4\nDATA binary_compressed\n";
  std::string soa;
  for (int k = 0; k < 12; ++k) put<float>(soa, 1.5f * k);
  const std::string good = compressed_pcd(header, soa);
  write_text(dir / "good.pcd", good);
  EXPECT_EQ(read_pcd((dir / "good.pcd").string()).size(), 4u);
  auto check = [&](const std::string& name, const std::string& content, const std::string& also) {
    write_text(dir / name, content);
    expect_io_error([&] { read_pcd((dir / name).string()); }, name, also);
  };
  check("no_sizes.pcd", header + "abc", "truncated before the two size words");
  check("truncated.pcd", good.substr(0, good.size() - 3), "truncated");
  // The uncompressed size must be POINTS x the record size (here 4 x 12).
  std::string wrong_size = good;
  const std::uint32_t forty = 40;
  std::memcpy(wrong_size.data() + header.size() + 4, &forty, 4);
  check("wrong_size.pcd", wrong_size, "is not POINTS 4 x 12");
  // A tiny file claiming a huge cloud is refused before anything is allocated.
  std::string huge =
      kHeader3 + "WIDTH 300000000\nHEIGHT 1\nPOINTS 300000000\nDATA binary_compressed\n";
  put<std::uint32_t>(huge, 4);
  put<std::uint32_t>(huge, 3600000000u);
  huge += "abcd";
  check("huge.pcd", huge, "cannot hold");
  // Corrupt LZF data: a back-reference before the start of the output.
  std::string corrupt = header;
  put<std::uint32_t>(corrupt, 3);
  put<std::uint32_t>(corrupt, 48);
  corrupt += std::string("\xe0\xff\xff", 3);
  check("corrupt.pcd", corrupt, "LZF data is corrupt");
}

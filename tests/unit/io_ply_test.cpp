#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "litamin2/io/io_error.hpp"
#include "litamin2/io/ply.hpp"
#include "support/io_test_support.hpp"

namespace fs = std::filesystem;
using litamin2::PointCloud;
using namespace litamin2::io;

namespace {

using litamin2::testing::expect_io_error;
using litamin2::testing::temp_dir;
using litamin2::testing::write_text;

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

PointCloud sample(bool with_intensity) {
  PointCloud cloud;
  for (int i = 0; i < 10; ++i) {
    cloud.points.emplace_back(0.5f * i, -1.25f * i, 3.0f + 0.001f * i);
    if (with_intensity) cloud.intensities.push_back(0.01f * i);
  }
  return cloud;
}

}  // namespace

TEST(IoPly, PointsRoundTrip) {
  const fs::path dir = temp_dir();
  for (bool with_i : {true, false}) {
    const fs::path file = dir / (with_i ? "i.ply" : "noi.ply");
    const PointCloud cloud = sample(with_i);
    write_ply_points(file.string(), cloud);
    const std::string text = read_text(file);
    EXPECT_EQ(text.rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u);
    EXPECT_NE(text.find("element vertex 10\n"), std::string::npos);
    EXPECT_EQ(text.find("property float intensity") != std::string::npos, with_i);
    const PointCloud back = read_ply_points(file.string());
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

TEST(IoPly, GenericVerticesRoundTrip) {
  const fs::path file = temp_dir() / "voxels.ply";
  const std::vector<std::string> names = {"x",   "y",   "z",   "c00", "c01",
                                          "c02", "c11", "c12", "c22", "count"};
  std::vector<float> values;
  for (int v = 0; v < 7; ++v) {
    for (std::size_t j = 0; j < names.size(); ++j) values.push_back(0.25f * v + j);
  }
  write_ply_vertices(file.string(), names, values);
  const PlyVertices back = read_ply_vertices(file.string());
  EXPECT_EQ(back.property_names, names);
  ASSERT_EQ(back.size(), 7u);
  ASSERT_EQ(back.values.size(), values.size());
  for (std::size_t k = 0; k < values.size(); ++k) EXPECT_EQ(back.values[k], values[k]);
  EXPECT_EQ(back.index_of("count"), 9);
  EXPECT_EQ(back.index_of("nope"), -1);
  EXPECT_EQ(back.at(6, 9), 0.25 * 6 + 9);
}

TEST(IoPly, WriterRejectsBadArguments) {
  const std::string file = (temp_dir() / "bad.ply").string();
  EXPECT_THROW(write_ply_vertices(file, {"x", "y"}, {1, 2, 3}), std::invalid_argument);
  EXPECT_THROW(write_ply_vertices(file, {"x", "x"}, {1, 2}), std::invalid_argument);
  EXPECT_THROW(write_ply_vertices(file, {"a b"}, {1}), std::invalid_argument);
  EXPECT_THROW(write_ply_vertices(file, {}, {}), std::invalid_argument);
}

TEST(IoPly, ReadsAsciiWithOtherElements) {
  const fs::path file = temp_dir() / "mesh.ply";
  write_text(file,
             "ply\r\nformat ascii 1.0\r\ncomment test\r\n"
             "element camera 1\nproperty float px\nproperty list uchar int ids\n"
             "element vertex 3\nproperty double x\nproperty double y\nproperty double z\n"
             "property uchar intensity\n"
             "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
             "0.5 2 7 8\n"
             "1 2 3 10\n4 5 6 20\n7 8 9 30\n"
             "3 0 1 2\n");
  const PointCloud cloud = read_ply_points(file.string());
  ASSERT_EQ(cloud.size(), 3u);
  EXPECT_EQ(cloud.points[2], Eigen::Vector3f(7, 8, 9));
  EXPECT_EQ(cloud.intensities[1], 20.0f);
}

TEST(IoPly, ErrorsNameTheFile) {
  const fs::path dir = temp_dir();
  const fs::path good = dir / "good.ply";
  write_ply_points(good.string(), sample(true));
  std::string bytes = read_text(good);
  bytes.resize(bytes.size() - 5);
  write_text(dir / "truncated.ply", bytes);
  expect_io_error([&] { read_ply_points((dir / "truncated.ply").string()); }, "truncated.ply",
                  "truncated");
  write_text(dir / "empty.ply", "");
  expect_io_error([&] { read_ply_points((dir / "empty.ply").string()); }, "empty.ply");
  write_text(dir / "notply.ply", "solid cube\nfacet normal 0 0 1\n");
  expect_io_error([&] { read_ply_points((dir / "notply.ply").string()); }, "notply.ply");
  write_text(dir / "noend.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n");
  expect_io_error([&] { read_ply_points((dir / "noend.ply").string()); }, "noend.ply",
                  "end_header");
  write_text(dir / "noxyz.ply",
             "ply\nformat ascii 1.0\nelement vertex 1\nproperty float a\nend_header\n1\n");
  expect_io_error([&] { read_ply_points((dir / "noxyz.ply").string()); }, "noxyz.ply");
  write_text(dir / "short_ascii.ply",
             "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
             "property float z\nend_header\n1 2 3\n");
  expect_io_error([&] { read_ply_points((dir / "short_ascii.ply").string()); }, "short_ascii.ply",
                  "truncated");
  expect_io_error([&] { read_ply_points((dir / "missing.ply").string()); }, "missing.ply");
  expect_io_error([&] { write_ply_points((dir / "nodir" / "out.ply").string(), sample(false)); },
                  "out.ply");
}

// Findings of the ply fuzz harness (tests/fuzz/corpus/ply/regression-*): rejected, not repaired.
TEST(IoPly, InvalidValuesAreRejectedNotRepaired) {
  const fs::path dir = temp_dir();
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty float intensity\nend_header\n";
  // A NaN point is a "no return" and dropped; the others are read.
  write_text(dir / "nan_point.ply", header + "1 2 3 4\nnan 0 0 1\n5 6 7 8\n");
  const PointCloud cloud = read_ply_points((dir / "nan_point.ply").string());
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_EQ(cloud.intensities[1], 8.0f);
  write_text(dir / "nan_intensity.ply", header + "1 2 3 4\n5 6 7 nan\n8 8 8 8\n");
  expect_io_error([&] { read_ply_points((dir / "nan_intensity.ply").string()); },
                  "nan_intensity.ply", "intensity");
  write_text(dir / "far.ply", header + "1 2 3 4\n5e300 6 7 8\n8 8 8 8\n");
  expect_io_error([&] { read_ply_points((dir / "far.ply").string()); }, "far.ply",
                  "beyond float range");
  // 2^60 items without a property would be iterated for ever.
  write_text(dir / "empty_element.ply",
             "ply\nformat binary_little_endian 1.0\nelement nothing 1152921504606846976\n"
             "element vertex 0\nproperty float x\nproperty float y\nproperty float z\n"
             "end_header\n");
  expect_io_error([&] { read_ply_points((dir / "empty_element.ply").string()); },
                  "empty_element.ply", "no property");
}

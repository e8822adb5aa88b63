// The export's map file formats: .ply and .pcd by extension, anything else refused before the
// store is opened; the PCD holds the same columns as the PLY (means as x y z, covariance,
// normal, count).

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "litamin2/aggregator/map_export.hpp"
#include "litamin2/io/pcd.hpp"

namespace {

using namespace litamin2;
using namespace litamin2::aggregator;
namespace fs = std::filesystem;

std::vector<Distribution> three_distributions() {
  std::vector<Distribution> map(3);
  for (std::size_t i = 0; i < map.size(); ++i) {
    map[i].mean = Eigen::Vector3d(1.0 + i, -2.0 * i, 0.5);
    map[i].cov = Eigen::Vector3d(0.04, 0.04, 0.0001 * (i + 1)).asDiagonal();  // flat: normal z
    map[i].count = static_cast<int>(10 + i);
  }
  return map;
}

fs::path temp_file(const std::string& name) {
  const fs::path dir = fs::path(LITAMIN2_BINARY_DIR) / "aggregator_map_export_test";
  fs::create_directories(dir);
  fs::remove(dir / name);
  return dir / name;
}

TEST(AggregatorMapExport, FormatFollowsTheExtension) {
  EXPECT_EQ(map_format("a/map.ply"), MapFormat::kPly);
  EXPECT_EQ(map_format("MAP.PLY"), MapFormat::kPly);
  EXPECT_EQ(map_format("map.pcd"), MapFormat::kPcd);
  EXPECT_EQ(map_format("x.Pcd"), MapFormat::kPcd);
  EXPECT_FALSE(map_format("map.txt"));
  EXPECT_FALSE(map_format("map"));
  EXPECT_FALSE(map_format("map.pcd.gz"));
}

TEST(AggregatorMapExport, OtherExtensionsAreRefusedBeforeTheStoreIsOpened) {
  ExportOptions options;
  options.store = temp_file("no_such.db").string();  // opening it would throw StoreError
  options.map_file = temp_file("map.xyz").string();
  EXPECT_THROW(export_store(options), std::invalid_argument);
  EXPECT_FALSE(fs::exists(options.map_file));
  EXPECT_FALSE(fs::exists(options.store));
}

TEST(AggregatorMapExport, PcdHoldsThePlyColumns) {
  const auto map = three_distributions();
  const fs::path path = temp_file("map.pcd");
  write_map_pcd(path.string(), map);

  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_EQ(bytes.rfind("# .PCD v0.7", 0), 0u) << "not a PCD: " << bytes.substr(0, 16);
  EXPECT_NE(bytes.find("FIELDS x y z c00 c01 c02 c11 c12 c22 nx ny nz count\n"), std::string::npos);
  EXPECT_NE(bytes.find("POINTS 3\n"), std::string::npos);
  const std::string data_line = "DATA binary\n";
  const std::size_t data = bytes.find(data_line);
  ASSERT_NE(data, std::string::npos);
  const std::size_t record = 12 * 4 + 4;  // 12 floats, one uint32
  ASSERT_EQ(bytes.size() - data - data_line.size(), 3 * record);

  // The reader takes the means back as the points (and ignores the other fields).
  const PointCloud cloud = io::read_pcd(path.string());
  ASSERT_EQ(cloud.size(), map.size());
  for (std::size_t i = 0; i < map.size(); ++i) {
    EXPECT_TRUE(cloud.points[i].isApprox(map[i].mean.cast<float>())) << i;
    const char* p = bytes.data() + data + data_line.size() + i * record;
    float c00 = 0.0f, c22 = 0.0f, nz = 0.0f;
    std::uint32_t count = 0;
    std::memcpy(&c00, p + 3 * 4, 4);
    std::memcpy(&c22, p + 8 * 4, 4);
    std::memcpy(&nz, p + 11 * 4, 4);
    std::memcpy(&count, p + 12 * 4, 4);
    EXPECT_FLOAT_EQ(c00, static_cast<float>(map[i].cov(0, 0)));
    EXPECT_FLOAT_EQ(c22, static_cast<float>(map[i].cov(2, 2)));
    EXPECT_NEAR(nz, 1.0f, 1e-5f);  // the least eigenvector of a flat covariance, nz >= 0
    EXPECT_EQ(count, static_cast<std::uint32_t>(map[i].count));
  }
}

}  // namespace

// fuzz_make_seeds: writes the seed corpora of tests/fuzz/corpus/<harness>/: valid inputs of
// every format (for libFuzzer to mutate) and one input per finding of the fuzzing campaign of
// issue 14 (regression-*: each must be rejected, none may crash or break a property). The
// corpus is committed; this tool regenerates it: fuzz_make_seeds tests/fuzz/corpus config
// (the shipped config files become config_yaml seeds).

#include "litamin2/dds/map_patch_conversion.hpp"
#include "litamin2/dds/map_tile_conversion.hpp"
#include "litamin2/dds/odometry_conversion.hpp"
#include "litamin2/dds/plain_scan_conversion.hpp"
#include "litamin2/dds/pointcloud2_conversion.hpp"
#include "litamin2/msg/MapPatchPubSubTypes.h"
#include "litamin2/msg/MapTilePubSubTypes.h"
#include "litamin2/store/record_codec.hpp"
#include "nav_msgs/msg/OdometryPubSubTypes.h"
#include "sensor_msgs/msg/PointCloud2PubSubTypes.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include <memory>

#include <liblzf/lzf.h>

namespace fs = std::filesystem;
using namespace litamin2;
namespace rtps = eprosima::fastrtps::rtps;

namespace {

fs::path root;

void write(const std::string& harness, const std::string& name, const std::string& bytes) {
  const fs::path dir = root / harness;
  fs::create_directories(dir);
  std::ofstream(dir / name, std::ios::binary) << bytes;
}

/// A selector byte followed by `body`.
std::string with_selector(std::uint8_t selector, const std::string& body) {
  return std::string(1, static_cast<char>(selector)) + body;
}

template <class PubSubType, class Msg>
std::string cdr(Msg& msg) {
  PubSubType type;
  rtps::SerializedPayload_t payload(type.getSerializedSizeProvider(&msg)());
  type.serialize(&msg, &payload);
  return std::string(reinterpret_cast<const char*>(payload.data), payload.length);
}

std::string floats(const std::vector<float>& v) {
  return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(float));
}

PointCloud small_cloud(bool intensity) {
  PointCloud cloud;
  for (int i = 0; i < 24; ++i) {
    cloud.points.emplace_back(0.5f * i, std::sin(0.3f * i) * 4.0f, 0.1f * (i % 5));
    if (intensity) cloud.intensities.push_back(static_cast<float>(i * 3));
  }
  return cloud;
}

void pointcloud2_seeds() {
  const std::string h = "pointcloud2_cdr";
  auto xyz = dds::to_pointcloud2(small_cloud(false), Stamp::from_seconds(10.5), "lidar");
  write(h, "xyz_float32", cdr<sensor_msgs::msg::PointCloud2PubSubType>(xyz));
  auto xyzi = dds::to_pointcloud2(small_cloud(true), Stamp::from_seconds(11.0), "lidar");
  write(h, "xyzi_float32", cdr<sensor_msgs::msg::PointCloud2PubSubType>(xyzi));
  // Per-point times as each vendor's driver writes them (the fields deskew reads).
  PointCloud timed = small_cloud(true);
  for (std::size_t i = 0; i < timed.points.size(); ++i) timed.times.push_back(0.004f * i);
  for (const dds::TimeLayout layout : {dds::TimeLayout::kVelodyne, dds::TimeLayout::kOuster,
                                       dds::TimeLayout::kHesai, dds::TimeLayout::kLivox}) {
    auto msg = dds::to_pointcloud2(timed, Stamp::from_seconds(12.0), "lidar", layout);
    write(h, std::string("times_") + dds::to_string(layout),
          cdr<sensor_msgs::msg::PointCloud2PubSubType>(msg));
  }
  // Organised 4 x 6, with "no return" NaN points.
  auto organised = xyzi;
  organised.height(4);
  organised.width(6);
  organised.row_step(6 * 16);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (int i : {3, 9, 17}) std::memcpy(organised.data().data() + 16 * i, &nan, 4);
  write(h, "organised_nan_points", cdr<sensor_msgs::msg::PointCloud2PubSubType>(organised));
  // float64 x, y, z and a uint16 intensity, big-endian, padded rows.
  sensor_msgs::msg::PointCloud2 f64;
  f64.header().frame_id("lidar");
  std::vector<sensor_msgs::msg::PointField> fields(4);
  const char* names[] = {"x", "y", "z", "intensity"};
  for (int k = 0; k < 4; ++k) {
    fields[k].name(names[k]);
    fields[k].offset(8 * k);
    fields[k].datatype(k < 3 ? 8 : 4);
    fields[k].count(1);
  }
  f64.fields(fields);
  f64.height(2);
  f64.width(3);
  f64.point_step(32);
  f64.row_step(3 * 32 + 8);
  f64.is_bigendian(true);
  f64.data(std::vector<std::uint8_t>(2 * (3 * 32 + 8), 0x3f));
  write(h, "float64_bigendian_padded", cdr<sensor_msgs::msg::PointCloud2PubSubType>(f64));

  // Findings.
  std::string bad_bool = cdr<sensor_msgs::msg::PointCloud2PubSubType>(xyz);
  bad_bool.back() = 2;  // is_dense
  write(h, "regression-bad-bool", bad_bool);
  std::string truncated = cdr<sensor_msgs::msg::PointCloud2PubSubType>(xyz);
  truncated.resize(truncated.size() / 2);
  write(h, "regression-truncated-sequence", truncated);
  std::string beyond = cdr<sensor_msgs::msg::PointCloud2PubSubType>(xyz);
  const std::uint32_t huge = 0x7fffffff;
  std::memcpy(beyond.data() + beyond.size() - 1 - xyz.data().size() - 4, &huge, 4);
  write(h, "regression-length-beyond-payload", beyond);
  auto nan_intensity = xyzi;
  std::memcpy(nan_intensity.data().data() + 16 * 5 + 12, &nan, 4);
  write(h, "regression-nan-intensity", cdr<sensor_msgs::msg::PointCloud2PubSubType>(nan_intensity));
}

Keyframe sample_keyframe(int distributions) {
  Keyframe kf;
  kf.key = {"car_1", 7};
  kf.stamp = Stamp::from_seconds(100.25);
  kf.odom_pose.linear() = Eigen::AngleAxisd(0.4, Eigen::Vector3d(0, 0.3, 1).normalized()).matrix();
  kf.odom_pose.translation() = Eigen::Vector3d(12.5, -3.0, 0.5);
  kf.covariance = Matrix6d::Identity() * 1e-4;
  kf.voxel_size = 3.0;
  for (int i = 0; i < distributions; ++i) {
    Distribution d;
    d.mean = Eigen::Vector3d(i, -0.5 * i, 0.25 * (i % 4));
    d.cov << 0.5, 0.0625, 0.03125, 0.0625, 0.25, 0.015625, 0.03125, 0.015625, 0.125;
    d.count = 5 + i;
    kf.distributions.push_back(d);
  }
  return kf;
}

void map_patch_seeds() {
  const std::string h = "map_patch_cdr";
  using Type = litamin2::msg::MapPatchPubSubType;
  const auto good = dds::to_map_patch(sample_keyframe(8), "car_1/odom");
  auto m = good;
  write(h, "valid", cdr<Type>(m));
  m = dds::to_map_patch(sample_keyframe(0), "car_1/odom");
  write(h, "valid_no_distributions", cdr<Type>(m));

  auto finding = [&](const std::string& name, auto change) {
    auto bad = good;
    change(bad);
    write(h, "regression-" + name, cdr<Type>(bad));
  };
  finding("translation-1e154", [](auto& p) { p.pose().position().x(1e154); });
  finding("translation-1e300", [](auto& p) { p.pose().position().z(-1e300); });
  finding("zero-quaternion", [](auto& p) {
    p.pose().orientation().x(0);
    p.pose().orientation().y(0);
    p.pose().orientation().z(0);
    p.pose().orientation().w(0);
  });
  finding("unnormalised-quaternion", [](auto& p) { p.pose().orientation().w(3.0); });
  finding("covariance-not-psd", [](auto& p) { p.covariance()[0] = -5.0; });
  finding("covariance-asymmetric", [](auto& p) { p.covariance()[1] = 0.5; });
  finding("distribution-count-0", [](auto& p) { p.distributions()[2].count(0); });
  finding("distribution-count-beyond-int",
          [](auto& p) { p.distributions()[3].count(0xffffffffu); });
  finding("distribution-negative-definite", [](auto& p) {
    p.distributions()[1].cov({-1, 0, 0, -1, 0, -1});
  });
  finding("voxel-size-1e-30", [](auto& p) { p.voxel_size(1e-30f); });
  finding("voxel-size-3e38", [](auto& p) { p.voxel_size(3e38f); });
  finding("keyframe-id-2-63", [](auto& p) { p.keyframe_id(std::uint64_t{1} << 63); });
  finding("bad-stream-id", [](auto& p) { p.stream_id("../etc"); });
  m = dds::to_map_patch(sample_keyframe(4097), "car_1/odom");  // the harness allows 4096
  write(h, "regression-too-many-distributions", cdr<Type>(m));
  std::string bytes = cdr<Type>(m = good);
  std::string truncated = bytes.substr(0, bytes.size() - 60);
  write(h, "regression-truncated-sequence", truncated);
  const std::uint32_t huge = 0x7fffffff;
  std::memcpy(bytes.data() + bytes.size() - 40 * good.distributions().size() - 4, &huge, 4);
  write(h, "regression-length-beyond-payload", bytes);
}

/// Tile (1, -2) of 20 m, 2 m voxels, n distributions inside it.
dds::MapTileData sample_tile(int n) {
  dds::MapTileData t;
  t.ix = 1;
  t.iy = -2;
  t.tile_size = 20.0;
  t.voxel_size = 2.0;
  t.revision = 1'700'000'000'000'000;
  t.stamp.nanoseconds = 1'700'000'000'000'000'000;
  t.frame_id = "map";
  t.anchor_stream = "car_1";
  t.keyframes = n > 0 ? 3 : 0;
  for (int i = 0; i < n; ++i) {
    Distribution d;
    d.mean = Eigen::Vector3d(21.0 + 0.5 * i, -39.0 + 0.25 * i, 0.1 * (i % 4));
    d.cov = Eigen::Vector3d(0.2, 0.1, 0.01).asDiagonal();
    d.count = 5 + i;
    t.distributions.push_back(d);
  }
  return t;
}

void map_tile_seeds() {
  const std::string h = "map_tile_cdr";
  using Type = litamin2::msg::MapTilePubSubType;
  const auto good = dds::to_map_tile(sample_tile(8));
  auto m = good;
  write(h, "valid", cdr<Type>(m));
  m = dds::to_map_tile(sample_tile(0));
  write(h, "valid_gone_tile", cdr<Type>(m));
  auto bad_seed = [&](const std::string& name, auto change) {
    auto bad = good;
    change(bad);
    write(h, "reject-" + name, cdr<Type>(bad));
  };
  bad_seed("tile-size-nan", [](auto& t) { t.tile_size(std::nanf("")); });
  bad_seed("voxel-size-0", [](auto& t) { t.voxel_size(0.0f); });
  bad_seed("key-beyond-bounds", [](auto& t) { t.ix(2'000'000'000); });
  bad_seed("stamp-nanosec", [](auto& t) { t.stamp().nanosec(2'000'000'000u); });
  bad_seed("empty-frame", [](auto& t) { t.frame_id(""); });
  bad_seed("no-keyframes", [](auto& t) { t.keyframes(0); });
  bad_seed("distribution-not-psd", [](auto& t) { t.distributions()[1].cov({-1, 0, 0, 1, 0, 1}); });
  bad_seed("mean-outside-tile", [](auto& t) { t.distributions()[2].mean({0.0f, 0.0f, 0.0f}); });
  m = dds::to_map_tile(sample_tile(4097));  // the harness allows 4096
  write(h, "reject-too-many-distributions", cdr<Type>(m));
  std::string bytes = cdr<Type>(m = good);
  write(h, "reject-truncated-sequence", bytes.substr(0, bytes.size() - 60));
}

void odometry_seeds() {
  const std::string h = "odometry_cdr";
  using Type = nav_msgs::msg::OdometryPubSubType;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() << 3, 4, 0.5;
  const auto good = dds::to_odometry(pose, Matrix6d::Identity() * 1e-3, Stamp::from_seconds(5),
                                     "car_1/odom", "car_1/base_link");
  auto m = good;
  write(h, "valid", cdr<Type>(m));
  m = good;
  m.twist().twist().linear().x(std::numeric_limits<double>::quiet_NaN());
  write(h, "regression-nan-twist", cdr<Type>(m));
  m = good;
  m.pose().pose().orientation().w(0.0);
  write(h, "regression-zero-quaternion", cdr<Type>(m));
  m = good;
  m.pose().covariance()[7] = -1.0;
  write(h, "regression-covariance-not-psd", cdr<Type>(m));
  std::string truncated = cdr<Type>(m = good);
  truncated.resize(truncated.size() - 100);
  write(h, "regression-truncated", truncated);
}

void record_codec_seeds() {
  const std::string h = "record_codec";
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.rotate(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()));
  pose.translation() << 1, 2, 3;
  const std::string p = store::encode_pose(pose);
  write(h, "pose", with_selector(0, p));
  write(h, "matrix6", with_selector(1, store::encode_matrix6(Matrix6d::Identity() * 0.01)));
  write(h, "distributions",
        with_selector(2, store::encode_distributions(sample_keyframe(3).distributions)));
  auto f64 = [](std::string bytes, int i, double v) {
    std::memcpy(bytes.data() + 8 * i, &v, 8);
    return bytes;
  };
  write(h, "regression-pose-not-orthonormal", with_selector(0, f64(p, 0, 2.0)));
  write(h, "regression-pose-reflection",
        with_selector(0, f64(store::encode_pose(Eigen::Isometry3d::Identity()), 8, -1.0)));
  write(h, "regression-pose-translation-1e300", with_selector(0, f64(p, 9, 1e300)));
  const std::string identity6 = store::encode_matrix6(Matrix6d::Identity());
  write(h, "regression-matrix-nan",
        with_selector(1, f64(identity6, 14, std::numeric_limits<double>::quiet_NaN())));
  write(h, "regression-matrix-asymmetric", with_selector(1, f64(identity6, 1, 0.5)));
  write(h, "regression-matrix-not-psd", with_selector(1, f64(identity6, 0, -1.0)));
  std::string d = store::encode_distributions(sample_keyframe(2).distributions);
  std::memset(d.data() + 36, 0, 4);
  write(h, "regression-distribution-count-0", with_selector(2, d));
}

void file_seeds() {
  const std::string kitti_bin = "kitti_bin";
  write(kitti_bin, "xyzi", with_selector(1, floats({1, 2, 3, 10, 4, 5, 6, 20, -7, 8, 0.5, 30})));
  write(kitti_bin, "xyz", with_selector(2, floats({1, 2, 3, 4, 5, 6, -7, 8, 0.5})));
  write(kitti_bin, "auto_48_bytes_corrected",
        with_selector(0x80, floats({1, 2, 3, 10, 4, 5, 6, 20, -7, 8, 0.5, 30})));
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float big = std::numeric_limits<float>::max();
  write(kitti_bin, "regression-nan-intensity",
        with_selector(1, floats({1, 2, 3, nan, 4, 5, 6, 1})));
  write(kitti_bin, "regression-correction-to-inf",
        with_selector(0x81, floats({big, 0, big, 1, 4, 5, 6, 1})));

  const std::string pcd = "pcd";
  const std::string header =
      "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 4\nTYPE F F F F\n"
      "COUNT 1 1 1 1\nWIDTH 3\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 3\n";
  write(pcd, "ascii", header + "DATA ascii\n1 2 3 4\n5 6 7 8\nnan nan nan nan\n");
  write(pcd, "binary", header + "DATA binary\n" + floats({1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12}));
  {
    // binary_compressed: the same three points field by field, LZF-compressed (as PCL writes).
    const std::string soa = floats({1, 5, 9, 2, 6, 10, 3, 7, 11, 4, 8, 12});
    std::string packed(soa.size() + 64, '\0');
    const unsigned int size = lzf_compress(soa.data(), static_cast<unsigned int>(soa.size()),
                                           packed.data(), static_cast<unsigned int>(packed.size()));
    const std::uint32_t sizes[2] = {size, static_cast<std::uint32_t>(soa.size())};
    write(pcd, "binary_compressed",
          header + "DATA binary_compressed\n" +
              std::string(reinterpret_cast<const char*>(sizes), sizeof sizes) +
              packed.substr(0, size));
  }
  write(pcd, "regression-nan-intensity", header + "DATA ascii\n1 2 3 4\n5 6 7 nan\n8 8 8 8\n");
  write(pcd, "regression-coordinate-beyond-float",
        header + "DATA ascii\n1 2 3 4\n5e300 6 7 8\n8 8 8 8\n");

  const std::string ply = "ply";
  const std::string xyzi =
      "property float x\nproperty float y\nproperty float z\n"
      "property float intensity\n";
  write(ply, "ascii_with_other_elements",
        "ply\nformat ascii 1.0\ncomment seed\nelement camera 1\nproperty float px\n"
        "property list uchar int ids\nelement vertex 4\n" +
            xyzi +
            "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
            "0.5 2 7 8\n1 2 3 10\n4 5 6 20\nnan 8 9 30\n3 0 1 2\n");
  write(ply, "binary_little_endian",
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\n" + xyzi + "end_header\n" +
            floats({1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12}));
  std::string be_doubles;
  for (double v : {1.0, 2.0, 3.0, -4.0, 5.5, 6.0}) {
    unsigned char b[8];
    std::memcpy(b, &v, 8);
    for (int i = 7; i >= 0; --i) be_doubles += static_cast<char>(b[i]);
  }
  write(ply, "binary_big_endian_double",
        "ply\nformat binary_big_endian 1.0\nelement vertex 2\nproperty double x\n"
        "property double y\nproperty double z\nend_header\n" +
            be_doubles);
  const std::string ascii_xyzi =
      "ply\nformat ascii 1.0\nelement vertex 2\n" + xyzi + "end_header\n";
  write(ply, "regression-nan-intensity", ascii_xyzi + "1 2 3 4\n5 6 7 nan\n");
  write(ply, "regression-coordinate-beyond-float", ascii_xyzi + "1 2 3 4\n5e300 6 7 8\n");
  // An element without properties and 2^60 items: nothing to read, but 2^60 iterations.
  write(ply, "regression-element-without-properties",
        "ply\nformat binary_little_endian 1.0\nelement nothing 1152921504606846976\n"
        "element vertex 1\n" +
            xyzi + "end_header\n" + floats({1, 2, 3, 4}));
}

/// A text seed of a harness whose first byte is a selector.
struct TextSeed {
  const char* harness;
  const char* name;
  std::uint8_t selector;
  const char* text;
};

const TextSeed kTextSeeds[] = {
    {"trajectory", "kitti", 0,
     "1 0 0 0 0 1 0 0 0 0 1 0\n0.9999978 5.272628e-04 -2.066935e-03 1 -5.296506e-04 0.9999992 "
     "-1.154865e-03 2 2.066324e-03 1.155958e-03 0.9999971 3\n"},
    {"trajectory", "tum", 1,
     "# t x y z qx qy qz qw\n0.5 1 2 3 0 0 0 1\n1.5 4 5 6 0 0 0.7071068 0.7071068\n"},
    {"trajectory", "regression-kitti-not-orthonormal", 0, "2 0 0 0 0 2 0 0 0 0 2 0\n"},
    {"trajectory", "regression-kitti-reflection", 0, "1 0 0 0 0 1 0 0 0 0 -1 0\n"},
    {"trajectory", "regression-tum-unnormalised", 1, "0 1 2 3 0 0 0 2\n"},
    {"trajectory", "regression-tum-zero-quaternion", 1, "0 1 2 3 0 0 0 0\n"},
    {"kitti_calib", "calib_txt", 255,
     "P0: 1 0 0 0 0 1 0 0 0 0 1 0\nTr: 4.276802e-04 -9.999672e-01 -8.084491e-03 -1.198459e-02 "
     "-7.210626e-03 8.081198e-03 -9.999413e-01 -5.403984e-02 9.999738e-01 4.859485e-04 "
     "-7.206933e-03 -2.921968e-01\n"},
    {"kitti_calib", "raw_rt", 255, "R: 1 0 0 0 1 0 0 0 1\nT: 0.1 0.2 0.3\n"},
    {"kitti_calib", "table", 3,
     "# table\n00-02: 1 0 0 0 0 1 0 0 0 0 1 0\n03: 0 -1 0 0 1 0 0 0 0 0 1 0\n"},
    {"kitti_calib", "regression-reflection", 255, "Tr: 1 0 0 0 0 1 0 0 0 0 -1 0\n"},
    {"config_yaml", "regression-daemon-mapping-key", 0, "? voxel_size: 3\n: 1\n"},
    {"config_yaml", "regression-daemon-tracker-mapping-key", 0,
     "discovery: {enabled: true}\ntracker:\n  voxelizer:\n    ? voxel_size: 3\n    : 2\n"},
    {"config_yaml", "regression-aggregator-mapping-key", 1, "? {voxel_size: 3}\n"},
    {"config_yaml", "regression-tracker-inf", 2,
     "registration: {sigma_icp: .inf, lambda: .inf}\nmap: {radius: .inf}\n"
     "keyframe: {distance: .inf}\nvoxelizer: {max_range: .inf}\n"},
    {"config_yaml", "regression-daemon-extrinsic-far", 0,
     "streams: [{id: a, extrinsic: {xyz: [1e300, 0, 0]}}]\n"},
    {"config_yaml", "daemon-streams", 0,
     "dds: {domain: 3}\nstreams:\n  - id: car_1\n    extrinsic: {xyz: [1, 0, 2], rpy_deg: [0, "
     "0, 90]}\n    tracker: {voxelizer: {voxel_size: 2}}\nlimits: {max_points_per_scan: 100000}\n"},
    {"config_yaml", "aggregator-limits", 1,
     "limits: {max_distributions_per_patch: 1000}\nmapper: {map_voxel_size: 2}\n"},
};

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

/// The shipped config files and every TextSeed.
void text_seeds(const fs::path& config_dir) {
  const char* shipped[] = {"litamin2d.yaml", "litamin2-aggregator.yaml", "tracker.yaml",
                           "mapper.yaml"};
  for (std::uint8_t i = 0; i < 4; ++i)
    write("config_yaml", std::string("shipped-") + shipped[i],
          with_selector(i, read_text(config_dir / shipped[i])));
  for (const TextSeed& seed : kTextSeeds)
    write(seed.harness, seed.name, with_selector(seed.selector, seed.text));
}

}  // namespace

/// PlainScan: the sample's memory, truncated after its points (the harness zero-fills the rest).
void plain_scan_seeds() {
  const std::string h = "plain_scan";
  auto scan = std::make_unique<litamin2_zero_copy::msg::PlainScan>();
  PointCloud cloud;
  for (int i = 0; i < 6; ++i) {
    cloud.points.emplace_back(1.0f + i, -2.0f * i, 0.5f);
    cloud.times.push_back(0.01f * i - 0.03f);
  }
  auto bytes = [&](std::size_t points) {
    return std::string(reinterpret_cast<const char*>(scan.get()), 80 + 16 * points);
  };
  dds::to_plain_scan(cloud, Stamp::from_seconds(7.5), "velodyne", *scan);
  write(h, "valid", bytes(6));
  scan->points()[2].x(std::numeric_limits<float>::quiet_NaN());
  write(h, "valid-non-finite-point", bytes(6));
  scan->points()[3].time(std::numeric_limits<float>::infinity());
  write(h, "reject-non-finite-time", bytes(6));
  dds::to_plain_scan(cloud, Stamp::from_seconds(7.5), "velodyne", *scan);
  scan->point_count(0xFFFFFFFFu);
  write(h, "reject-point-count", bytes(6));
  dds::to_plain_scan(cloud, Stamp::from_seconds(7.5), "velodyne", *scan);
  scan->frame_id().fill('x');
  write(h, "reject-frame-id", bytes(6));
}

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s CORPUS_DIR CONFIG_DIR\n", argv[0]);
    return 2;
  }
  root = argv[1];
  pointcloud2_seeds();
  map_patch_seeds();
  map_tile_seeds();
  odometry_seeds();
  plain_scan_seeds();
  record_codec_seeds();
  file_seeds();
  text_seeds(argv[2]);
  std::printf("seeds written to %s\n", root.c_str());
  return 0;
}

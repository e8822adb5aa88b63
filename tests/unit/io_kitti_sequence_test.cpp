#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "litamin2/io/io_error.hpp"
#include "litamin2/io/kitti_bin.hpp"
#include "litamin2/io/kitti_sequence.hpp"
#include "litamin2/io/pcd.hpp"
#include "litamin2/io/trajectory.hpp"
#include "support/io_test_support.hpp"

namespace fs = std::filesystem;
using litamin2::PointCloud;
using namespace litamin2::io;

namespace {

using litamin2::testing::expect_io_error;
using litamin2::testing::temp_dir;
using litamin2::testing::write_text;

/// A scan whose first point encodes its index, so load order can be checked.
PointCloud scan(int index, int n = 5) {
  PointCloud cloud;
  for (int i = 0; i < n; ++i) {
    cloud.points.emplace_back(10.0f + static_cast<float>(index), static_cast<float>(i), 0.5f);
    cloud.intensities.push_back(0.5f);
  }
  return cloud;
}

const char* kTr =
    "4.276802385584e-04 -9.999672484946e-01 -8.084491683471e-03 -1.198459927713e-02 "
    "-7.210626507497e-03 8.081198471645e-03 -9.999413164504e-01 -5.403984729748e-02 "
    "9.999738645903e-01 4.859485810390e-04 -7.206933692422e-03 -2.921968648686e-01";

std::vector<Eigen::Isometry3d> straight_poses(int n) {
  std::vector<Eigen::Isometry3d> poses;
  for (int i = 0; i < n; ++i) {
    Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
    p.translation() = Eigen::Vector3d(0, 0, 0.8 * i);  // camera z is forward
    poses.push_back(p);
  }
  return poses;
}

/// Writes <root>/sequences/07 with 3 scans, calib.txt and times.txt; poses in <root>/poses/07.txt.
fs::path make_kitti_dataset(const fs::path& root, int n_times = 3) {
  const fs::path seq = root / "sequences" / "07";
  fs::create_directories(seq / "velodyne");
  for (int i = 2; i >= 0; --i) {  // written out of order on purpose
    write_kitti_bin((seq / "velodyne" / ("00000" + std::to_string(i) + ".bin")).string(), scan(i));
  }
  write_text(seq / "velodyne" / "README", "not a scan");
  write_text(seq / "calib.txt", std::string("P0: 1 0 0 0 0 1 0 0 0 0 1 0\r\nTr: ") + kTr + "\r\n");
  std::string times;
  for (int i = 0; i < n_times; ++i) times += std::to_string(0.103 * i) + "e+00\r\n";
  write_text(seq / "times.txt", times);
  fs::create_directories(root / "poses");
  write_kitti_poses((root / "poses" / "07.txt").string(), straight_poses(3));
  return seq;
}

const std::string kShared = LITAMIN2_SHARED_DATA_DIR;

}  // namespace

TEST(IoScanSequence, KittiDatasetLayout) {
  const fs::path seq_dir = make_kitti_dataset(temp_dir());
  const ScanSequence seq(seq_dir.string());
  EXPECT_TRUE(seq.is_kitti());
  ASSERT_EQ(seq.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(fs::path(seq.path(i)).filename(), "00000" + std::to_string(i) + ".bin");
    EXPECT_NEAR(seq.timestamp(i), 0.103 * static_cast<double>(i), 1e-12);
    const PointCloud cloud = seq.load(i);
    ASSERT_EQ(cloud.size(), 5u);
    EXPECT_EQ(cloud.points[0].x(), 10.0f + static_cast<float>(i));
  }
  ASSERT_TRUE(seq.velo_to_cam().has_value());
  EXPECT_DOUBLE_EQ(seq.velo_to_cam()->matrix()(0, 0), 4.276802385584e-04);
  ASSERT_TRUE(seq.ground_truth_cam().has_value());
  ASSERT_EQ(seq.ground_truth_cam()->size(), 3u);
  EXPECT_NEAR((*seq.ground_truth_cam())[2].translation().z(), 1.6, 1e-12);
  // Camera forward (z) motion is Velodyne forward (x) motion.
  const auto velo = seq.ground_truth_velo();
  ASSERT_TRUE(velo.has_value());
  EXPECT_NEAR((*velo)[2].translation().x(), 1.6, 0.02);
  // A trailing slash still finds <dataset>/poses/07.txt.
  EXPECT_TRUE(ScanSequence(seq_dir.string() + "/").ground_truth_cam().has_value());
  EXPECT_THROW(seq.load(3), std::out_of_range);
  EXPECT_THROW(seq.path(3), std::out_of_range);
  EXPECT_THROW(seq.timestamp(3), std::out_of_range);
}

TEST(IoScanSequence, PosesTxtInFolderAndDefaultTimes) {
  const fs::path seq_dir = make_kitti_dataset(temp_dir());
  fs::remove(seq_dir / "times.txt");
  fs::remove(seq_dir / "calib.txt");
  fs::remove_all(seq_dir.parent_path().parent_path() / "poses");
  {
    const ScanSequence seq(seq_dir.string());
    EXPECT_FALSE(seq.velo_to_cam().has_value());
    EXPECT_FALSE(seq.ground_truth_cam().has_value());
    EXPECT_FALSE(seq.ground_truth_velo().has_value());
    EXPECT_DOUBLE_EQ(seq.timestamp(2), 0.2);
  }
  write_kitti_poses((seq_dir / "poses.txt").string(), straight_poses(3));
  const ScanSequence seq(seq_dir.string());
  ASSERT_TRUE(seq.ground_truth_cam().has_value());
  EXPECT_EQ(seq.ground_truth_cam()->size(), 3u);
}

TEST(IoScanSequence, VerticalCorrectionOptionIsHonoured) {
  const fs::path seq_dir = make_kitti_dataset(temp_dir());
  KittiBinOptions opt;
  opt.vertical_angle_correction_deg = 0.205;
  const ScanSequence seq(seq_dir.string(), opt);
  const PointCloud corrected = seq.load(0);
  const PointCloud raw = ScanSequence(seq_dir.string()).load(0);
  EXPECT_NEAR(corrected.points[0].z() - raw.points[0].z(), 10.0 * 0.205 * M_PI / 180.0, 1e-4);
}

TEST(IoScanSequence, CountMismatchesThrow) {
  {
    const fs::path seq_dir = make_kitti_dataset(temp_dir(), 4);
    expect_io_error([&] { ScanSequence seq(seq_dir.string()); }, "times.txt", "4 timestamps");
  }
  {
    const fs::path seq_dir = make_kitti_dataset(temp_dir());
    write_kitti_poses((seq_dir.parent_path().parent_path() / "poses" / "07.txt").string(),
                      straight_poses(2));
    expect_io_error([&] { ScanSequence seq(seq_dir.string()); }, "07.txt", "2 poses");
  }
  {
    const fs::path seq_dir = make_kitti_dataset(temp_dir());
    write_text(seq_dir / "calib.txt", "P0: 1 2 3\n");
    expect_io_error([&] { ScanSequence seq(seq_dir.string()); }, "calib.txt");
  }
}

TEST(IoScanSequence, PlainFolderOfBinAndPcd) {
  const fs::path dir = temp_dir();
  write_kitti_bin((dir / "b_1.bin").string(), scan(1));
  write_pcd_binary((dir / "a_0.pcd").string(), scan(0, 4));
  write_kitti_bin((dir / "c_2.BIN").string(), scan(2));
  write_text(dir / "notes.txt", "ignored");
  fs::create_directories(dir / "sub.bin");  // a folder, not a scan
  const ScanSequence seq(dir.string());
  EXPECT_FALSE(seq.is_kitti());
  ASSERT_EQ(seq.size(), 3u);
  EXPECT_EQ(seq.load(0).size(), 4u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(seq.load(i).points[0].x(), 10.0f + static_cast<float>(i));
    EXPECT_DOUBLE_EQ(seq.timestamp(i), 0.1 * static_cast<double>(i));
  }
  EXPECT_FALSE(seq.velo_to_cam().has_value());
  EXPECT_FALSE(seq.ground_truth_cam().has_value());
}

TEST(IoScanSequence, EmptyOrMissingFolderThrows) {
  const fs::path dir = temp_dir();
  fs::create_directories(dir / "empty_folder");
  expect_io_error([&] { ScanSequence seq((dir / "empty_folder").string()); }, "empty_folder");
  expect_io_error([&] { ScanSequence seq((dir / "missing_folder").string()); }, "missing_folder");
  fs::create_directories(dir / "kitti_empty" / "velodyne");
  expect_io_error([&] { ScanSequence seq((dir / "kitti_empty").string()); }, "kitti_empty");
  write_text(dir / "a_file.bin", "");
  expect_io_error([&] { ScanSequence seq((dir / "a_file.bin").string()); }, "a_file.bin");
}

TEST(IoScanSequence, SharedScansAsPlainFolder) {
  const std::string dir = kShared + "/kitti/seq00_frames_xyz";
  if (!fs::exists(dir)) GTEST_SKIP() << "shared KITTI scans not found under " << dir;
  const ScanSequence seq(dir);
  ASSERT_EQ(seq.size(), 2u);
  EXPECT_EQ(seq.load(0).size(), 124668u);
  EXPECT_EQ(seq.load(1).size(), 124605u);
}

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "litamin2/io/io_error.hpp"
#include "litamin2/io/kitti_calib.hpp"
#include "litamin2/io/trajectory.hpp"
#include "support/io_test_support.hpp"

namespace fs = std::filesystem;
using namespace litamin2::io;

namespace {

using litamin2::testing::expect_io_error;
using litamin2::testing::temp_dir;
using litamin2::testing::write_text;

// Tr of KITTI odometry sequences 00-02.
const char* kTr00 =
    "4.276802385584e-04 -9.999672484946e-01 -8.084491683471e-03 -1.198459927713e-02 "
    "-7.210626507497e-03 8.081198471645e-03 -9.999413164504e-01 -5.403984729748e-02 "
    "9.999738645903e-01 4.859485810390e-04 -7.206933692422e-03 -2.921968648686e-01";
const char* kP0 =
    "7.188560000000e+02 0.000000000000e+00 6.071928000000e+02 0.000000000000e+00 "
    "0.000000000000e+00 7.188560000000e+02 1.852157000000e+02 0.000000000000e+00 "
    "0.000000000000e+00 0.000000000000e+00 1.000000000000e+00 0.000000000000e+00";

void expect_tr00(const Eigen::Isometry3d& tr) {
  EXPECT_DOUBLE_EQ(tr.matrix()(0, 0), 4.276802385584e-04);
  EXPECT_DOUBLE_EQ(tr.matrix()(0, 3), -1.198459927713e-02);
  EXPECT_DOUBLE_EQ(tr.matrix()(2, 0), 9.999738645903e-01);
  EXPECT_DOUBLE_EQ(tr.matrix()(2, 3), -2.921968648686e-01);
  EXPECT_EQ(tr.matrix().row(3), Eigen::RowVector4d(0, 0, 0, 1));
}

const std::string kShared = LITAMIN2_SHARED_DATA_DIR;

}  // namespace

TEST(IoKittiCalib, SequenceCalibTxt) {
  const fs::path dir = temp_dir();
  const std::string p = kP0;
  write_text(dir / "calib.txt", "P0: " + p + "\r\nP1: " + p + "\r\nP2: " + p + "\r\nP3: " + p +
                                    "\r\nTr: " + kTr00 + "\r\n");
  expect_tr00(read_kitti_velo_to_cam((dir / "calib.txt").string()));
  // The sequence number is ignored for a calib.txt; a folder means its calib.txt.
  expect_tr00(read_kitti_velo_to_cam((dir / "calib.txt").string(), 7));
  expect_tr00(read_kitti_velo_to_cam(dir.string()));
}

TEST(IoKittiCalib, RawDataStyles) {
  const fs::path dir = temp_dir();
  write_text(dir / "raw.txt",
             std::string("calib_time: 15-Mar-2012 11:37:16\nTr_velo_to_cam: ") + kTr00 + "\n");
  expect_tr00(read_kitti_velo_to_cam((dir / "raw.txt").string()));
  write_text(dir / "calib_velo_to_cam.txt",
             "calib_time: 15-Mar-2012 11:37:16\n"
             "R: 4.276802385584e-04 -9.999672484946e-01 -8.084491683471e-03 "
             "-7.210626507497e-03 8.081198471645e-03 -9.999413164504e-01 "
             "9.999738645903e-01 4.859485810390e-04 -7.206933692422e-03\n"
             "T: -1.198459927713e-02 -5.403984729748e-02 -2.921968648686e-01\n"
             "delta_f: 0.000000e+00 0.000000e+00\n");
  expect_tr00(read_kitti_velo_to_cam((dir / "calib_velo_to_cam.txt").string()));
}

TEST(IoKittiCalib, SharedTable) {
  const std::string table = kShared + "/kitti/calib_Tr_velo_to_cam.txt";
  if (!fs::exists(table)) GTEST_SKIP() << "shared calib table not found: " << table;
  const Eigen::Isometry3d tr00 = read_kitti_velo_to_cam(table, kitti_sequence_number("00"));
  expect_tr00(tr00);
  const Eigen::Matrix3d r = tr00.linear();
  EXPECT_LT((r.transpose() * r - Eigen::Matrix3d::Identity()).norm(), 1e-6);
  EXPECT_NEAR(r.determinant(), 1.0, 1e-6);
  // 02 shares the 00-02 row, 03 has its own, 05 and 10 are in 04-10.
  EXPECT_TRUE(read_kitti_velo_to_cam(table, 2).isApprox(tr00));
  const Eigen::Isometry3d tr03 = read_kitti_velo_to_cam(table, 3);
  EXPECT_DOUBLE_EQ(tr03.matrix()(0, 0), 2.347736981471e-04);
  EXPECT_DOUBLE_EQ(read_kitti_velo_to_cam(table, 5).matrix()(0, 0), -1.857739385241e-03);
  EXPECT_DOUBLE_EQ(read_kitti_velo_to_cam(table, 10).matrix()(2, 3), -3.339968064433e-01);
  expect_io_error([&] { read_kitti_velo_to_cam(table); }, "calib_Tr_velo_to_cam.txt",
                  "sequence number is required");
  expect_io_error([&] { read_kitti_velo_to_cam(table, 11); }, "calib_Tr_velo_to_cam.txt",
                  "sequence 11");
}

TEST(IoKittiCalib, SharedGroundTruthInVelodyneFrame) {
  // README of the shared data: with GT 00 lines 1-2 and Tr(00), the Velodyne motion between
  // frames 0 and 1 is t = (0.859, 0.047, 0.022) m.
  const std::string table = kShared + "/kitti/calib_Tr_velo_to_cam.txt";
  const std::string poses = kShared + "/kitti/poses/00.txt";
  if (!fs::exists(table) || !fs::exists(poses)) GTEST_SKIP() << "shared KITTI data not found";
  const auto gt = read_kitti_poses(poses);
  const auto velo = cam_to_velo_trajectory(gt, read_kitti_velo_to_cam(table, 0));
  ASSERT_EQ(velo.size(), gt.size());
  EXPECT_TRUE(velo[0].isApprox(Eigen::Isometry3d::Identity(), 1e-6));
  EXPECT_NEAR(velo[1].translation().x(), 0.859, 0.002);
  EXPECT_NEAR(velo[1].translation().y(), 0.047, 0.002);
  EXPECT_NEAR(velo[1].translation().z(), 0.022, 0.002);
}

TEST(IoKittiCalib, TrajectoryConversionsRoundTrip) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto random_pose = [&] {
    Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
    p.linear() = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().matrix();
    p.translation() = 10.0 * Eigen::Vector3d(u(rng), u(rng), u(rng));
    return p;
  };
  const Eigen::Isometry3d tr = random_pose();
  std::vector<Eigen::Isometry3d> cam;
  for (int i = 0; i < 10; ++i) cam.push_back(random_pose());
  const auto velo = cam_to_velo_trajectory(cam, tr);
  ASSERT_EQ(velo.size(), cam.size());
  EXPECT_TRUE(velo[0].isApprox(Eigen::Isometry3d::Identity(), 1e-12));
  for (std::size_t i = 0; i < cam.size(); ++i) {
    const Eigen::Isometry3d expected = tr.inverse() * cam[0].inverse() * cam[i] * tr;
    EXPECT_TRUE(velo[i].isApprox(expected, 1e-9)) << i;
  }
  const auto cam_back = velo_to_cam_trajectory(velo, tr);
  for (std::size_t i = 0; i < cam.size(); ++i) {
    EXPECT_TRUE(cam_back[i].isApprox(cam[0].inverse() * cam[i], 1e-9)) << i;
  }
  const Eigen::Isometry3d p = random_pose();
  EXPECT_TRUE(velo_pose_to_cam(cam_pose_to_velo(p, tr), tr).isApprox(p, 1e-12));
  EXPECT_TRUE(cam_to_velo_trajectory({}, tr).empty());
}

TEST(IoKittiCalib, SequenceNumbers) {
  EXPECT_EQ(kitti_sequence_number("00"), 0);
  EXPECT_EQ(kitti_sequence_number("07"), 7);
  EXPECT_EQ(kitti_sequence_number("10"), 10);
  EXPECT_EQ(kitti_sequence_number("/data/kitti/sequences/05/"), 5);
  EXPECT_THROW(kitti_sequence_number("seq"), std::invalid_argument);
  EXPECT_THROW(kitti_sequence_number(""), std::invalid_argument);
}

TEST(IoKittiCalib, ErrorsNameTheFile) {
  const fs::path dir = temp_dir();
  auto check = [&](const std::string& name, const std::string& content, const std::string& also,
                   std::optional<int> seq = std::nullopt) {
    write_text(dir / name, content);
    expect_io_error([&] { read_kitti_velo_to_cam((dir / name).string(), seq); }, name, also);
  };
  check("eleven.txt", "Tr: 1 0 0 0 0 1 0 0 0 0 1\n", "11 values");
  check("notnum.txt", "Tr: 1 0 0 0 0 1 0 0 0 0 1 abc\n", "abc");
  check("skew.txt", "Tr: 1 0 0 0 0 2 0 0 0 0 1 0\n", "orthonormal");
  // Regression (issue 14): a reflection is orthonormal but not a rotation.
  check("reflection.txt", "Tr: 1 0 0 0 0 1 0 0 0 0 -1 0\n", "reflection");
  check("nokey.txt", "P0: 1 2 3\n", "no 'Tr:'");
  check("nocolon.txt", "hello world\n", "line 1");
  check("empty_calib.txt", "", "empty_calib.txt");
  check("badrow.txt", "00-02: 1 0 0 0 0 1 0 0 0 0 1\n", "11 values", 1);
  expect_io_error([&] { read_kitti_velo_to_cam((dir / "missing_calib.txt").string()); },
                  "missing_calib.txt");
  fs::create_directories(dir / "seq_without_calib");
  expect_io_error([&] { read_kitti_velo_to_cam((dir / "seq_without_calib").string()); },
                  "seq_without_calib");
}

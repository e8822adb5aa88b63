#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "litamin2/io/io_error.hpp"
#include "litamin2/io/trajectory.hpp"
#include "support/io_test_support.hpp"

namespace fs = std::filesystem;
using namespace litamin2::io;

namespace {

using litamin2::testing::expect_io_error;
using litamin2::testing::temp_dir;
using litamin2::testing::write_text;

std::vector<Eigen::Isometry3d> random_poses(std::size_t n) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::Isometry3d> poses;
  for (std::size_t i = 0; i < n; ++i) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().matrix();
    pose.translation() = Eigen::Vector3d(u(rng), u(rng), u(rng)) * 1000.0;
    poses.push_back(pose);
  }
  return poses;
}

const std::string kShared = LITAMIN2_SHARED_DATA_DIR;

}  // namespace

TEST(IoTrajectory, KittiRoundTripIsExact) {
  const fs::path file = temp_dir() / "poses.txt";
  const auto poses = random_poses(50);
  write_kitti_poses(file.string(), poses);
  const auto back = read_kitti_poses(file.string());
  ASSERT_EQ(back.size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_LT((back[i].matrix() - poses[i].matrix()).cwiseAbs().maxCoeff(), 1e-12) << i;
  }
}

TEST(IoTrajectory, KittiAcceptsCrlfAndTrailingBlankLines) {
  const fs::path file = temp_dir() / "crlf.txt";
  write_text(file,
             "1 0 0 1  0 1 0 2  0 0 1 3\r\n"
             "1 0 0 4 0 1 0 5 0 0 1 +6\r\n"
             "\r\n  \n\n");
  const auto poses = read_kitti_poses(file.string());
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_EQ(poses[0].translation(), Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(poses[1].translation(), Eigen::Vector3d(4, 5, 6));
  EXPECT_TRUE(poses[1].linear().isIdentity());
}

TEST(IoTrajectory, KittiErrorsNameFileAndLine) {
  const fs::path dir = temp_dir();
  write_text(dir / "wrong_count.txt",
             "1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 0 0 1 0 0 0 0 1\n");
  expect_io_error([&] { read_kitti_poses((dir / "wrong_count.txt").string()); }, "wrong_count.txt",
                  "line 3");
  write_text(dir / "not_number.txt", "1 0 0 0 0 1 0 0 0 0 1 x0\n");
  expect_io_error([&] { read_kitti_poses((dir / "not_number.txt").string()); }, "not_number.txt",
                  "line 1");
  write_text(dir / "gap.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n\n1 0 0 0 0 1 0 0 0 0 1 0\n");
  expect_io_error([&] { read_kitti_poses((dir / "gap.txt").string()); }, "gap.txt", "line 2");
  write_text(dir / "empty_poses.txt", "");
  expect_io_error([&] { read_kitti_poses((dir / "empty_poses.txt").string()); }, "empty_poses.txt");
  expect_io_error([&] { read_kitti_poses((dir / "missing_poses.txt").string()); },
                  "missing_poses.txt");
  expect_io_error([&] { write_kitti_poses((dir / "nodir" / "out.txt").string(), {}); }, "out.txt");
}

TEST(IoTrajectory, KittiRejectsNonRotations) {
  // Regressions (issue 14): a pose file's matrix is taken as is, so it must be a rigid motion.
  const fs::path dir = temp_dir();
  write_text(dir / "scaled.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n2 0 0 0 0 2 0 0 0 0 2 0\n");
  expect_io_error([&] { read_kitti_poses((dir / "scaled.txt").string()); }, "line 2",
                  "not orthonormal");
  write_text(dir / "reflection.txt", "1 0 0 0 0 1 0 0 0 0 -1 0\n");
  expect_io_error([&] { read_kitti_poses((dir / "reflection.txt").string()); }, "line 1",
                  "reflection");
  write_text(dir / "far.txt", "1 0 0 1e300 0 1 0 0 0 0 1 0\n");
  expect_io_error([&] { read_kitti_poses((dir / "far.txt").string()); }, "line 1",
                  "translation holds");
  // Rounding to 7 digits (KITTI's ground truth) is accepted.
  write_text(dir / "rounded.txt",
             "0.9999978 5.272628e-04 -2.066935e-03 1 -5.296506e-04 "
             "0.9999992 -1.154865e-03 2 2.066324e-03 1.155958e-03 0.9999971 3\n");
  EXPECT_EQ(read_kitti_poses((dir / "rounded.txt").string()).size(), 1u);
}

TEST(IoTrajectory, SharedKittiGroundTruth00) {
  const std::string file = kShared + "/kitti/poses/00.txt";
  if (!fs::exists(file)) GTEST_SKIP() << "shared KITTI poses not found: " << file;
  const auto poses = read_kitti_poses(file);
  ASSERT_EQ(poses.size(), 4541u);
  // The file stores the identity to 7 digits (e.g. 9.999999e-01).
  EXPECT_LT((poses[0].matrix() - Eigen::Matrix4d::Identity()).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_DOUBLE_EQ(poses[1].matrix()(0, 0), 9.999978e-01);
  EXPECT_DOUBLE_EQ(poses[1].matrix()(0, 1), 5.272628e-04);
  EXPECT_DOUBLE_EQ(poses[1].matrix()(0, 2), -2.066935e-03);
  EXPECT_DOUBLE_EQ(poses[1].matrix()(0, 3), -4.690294e-02);
  EXPECT_EQ(poses[1].matrix().row(3), Eigen::RowVector4d(0, 0, 0, 1));
}

TEST(IoTrajectory, TumRoundTripIsExact) {
  const fs::path file = temp_dir() / "traj.tum";
  const auto poses = random_poses(30);
  std::vector<TimedPose> timed;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    timed.push_back({1305031102.175304 + 0.1 * static_cast<double>(i), poses[i]});
  }
  write_tum(file.string(), timed);
  const auto back = read_tum(file.string());
  ASSERT_EQ(back.size(), timed.size());
  for (std::size_t i = 0; i < timed.size(); ++i) {
    EXPECT_EQ(back[i].time, timed[i].time);
    EXPECT_LT((back[i].pose.matrix() - timed[i].pose.matrix()).cwiseAbs().maxCoeff(), 1e-9) << i;
  }
}

TEST(IoTrajectory, TumSkipsCommentsAndRemovesTheRoundingOfQuaternions) {
  const fs::path file = temp_dir() / "c.tum";
  write_text(file,
             "# timestamp tx ty tz qx qy qz qw\r\n"
             "0.5 1 2 3 0 0 0 1.0000001\r\n"
             "\n"
             "  # another comment\n"
             "1.5 4 5 6 0 0 0.7071068 0.7071068\n");
  const auto poses = read_tum(file.string());
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_EQ(poses[0].time, 0.5);
  EXPECT_TRUE(poses[0].pose.linear().isIdentity(1e-12));
  EXPECT_EQ(poses[1].pose.translation(), Eigen::Vector3d(4, 5, 6));
  const Eigen::Matrix3d rz90 = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).matrix();
  EXPECT_LT((poses[1].pose.linear() - rz90).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(IoTrajectory, TumErrorsNameFileAndLine) {
  const fs::path dir = temp_dir();
  write_text(dir / "seven.tum", "# c\n0 1 2 3 0 0 0 1\n0 1 2 3 0 0 1\n");
  expect_io_error([&] { read_tum((dir / "seven.tum").string()); }, "seven.tum", "line 3");
  write_text(dir / "zeroq.tum", "0 1 2 3 0 0 0 0\n");
  expect_io_error([&] { read_tum((dir / "zeroq.tum").string()); }, "zeroq.tum", "line 1");
  // Regressions (issue 14): an unnormalised quaternion is rejected, not normalised.
  write_text(dir / "twice.tum", "0 1 2 3 0 0 0 1\n1 1 2 3 0 0 0 2\n");
  expect_io_error([&] { read_tum((dir / "twice.tum").string()); }, "line 2",
                  "not a unit quaternion (norm 2)");
  write_text(dir / "far.tum", "0 1e300 2 3 0 0 0 1\n");
  expect_io_error([&] { read_tum((dir / "far.tum").string()); }, "line 1", "translation holds");
  write_text(dir / "only_comments.tum", "# nothing\n");
  expect_io_error([&] { read_tum((dir / "only_comments.tum").string()); }, "only_comments.tum");
  expect_io_error([&] { read_tum((dir / "missing.tum").string()); }, "missing.tum");
}

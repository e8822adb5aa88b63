// The written folder has the KITTI odometry layout and reads back with io::ScanSequence.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "litamin2/io/kitti_calib.hpp"
#include "litamin2/io/kitti_sequence.hpp"
#include "litamin2/sim/builtin_trajectory.hpp"
#include "litamin2/sim/fleet.hpp"
#include "litamin2/sim/raycaster.hpp"
#include "litamin2/sim/sequence_writer.hpp"
#include "litamin2/sim/world.hpp"

namespace sim = litamin2::sim;
namespace io = litamin2::io;
namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::path(LITAMIN2_BINARY_DIR) / "sim_test_output" / name;
  fs::remove_all(dir);
  return dir;
}

}  // namespace

TEST(SimSequenceWriter, WritesKittiLayoutReadBackByScanSequence) {
  const auto path = sim::builtin_trajectory("loop");
  const std::vector<Eigen::Isometry3d> poses(path.begin() + 20, path.begin() + 26);
  const sim::World world(path, 11);
  sim::Raycaster rc(world);
  sim::SequenceWriteOptions opt;
  opt.model = sim::LidarModel::vlp16();
  opt.velo_to_cam = sim::kitti_default_velo_to_cam();
  opt.seed = 4;
  std::vector<std::size_t> sizes;
  opt.on_scan = [&](std::size_t, const litamin2::PointCloud& c) { sizes.push_back(c.size()); };
  const fs::path dir = fresh_dir("seq");
  const auto result = sim::write_sequence(dir.string(), rc, poses, opt);
  EXPECT_EQ(result.frames, poses.size());

  for (const char* f :
       {"poses.txt", "calib.txt", "times.txt", "velodyne/000000.bin", "velodyne/000005.bin"}) {
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  }
  EXPECT_FALSE(fs::exists(dir / "velodyne/000006.bin"));
  // calib.txt has a Tr: line that io reads back.
  std::ifstream calib(dir / "calib.txt");
  std::string text((std::istreambuf_iterator<char>(calib)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\nTr: "), std::string::npos);
  EXPECT_NE(text.find("P0: "), std::string::npos);

  const io::ScanSequence seq(dir.string());
  ASSERT_EQ(seq.size(), poses.size());
  EXPECT_TRUE(seq.is_kitti());
  for (std::size_t i = 0; i < seq.size(); ++i) {
    EXPECT_NEAR(seq.timestamp(i), 0.1 * i, 1e-9);
    const auto cloud = seq.load(i);
    EXPECT_EQ(cloud.size(), sizes[i]);
    EXPECT_EQ(cloud.intensities.size(), cloud.size());
  }
  ASSERT_TRUE(seq.velo_to_cam().has_value());
  EXPECT_TRUE(seq.velo_to_cam()->isApprox(opt.velo_to_cam, 1e-9));
  ASSERT_TRUE(seq.ground_truth_cam().has_value());
  const auto& gt = *seq.ground_truth_cam();
  ASSERT_EQ(gt.size(), poses.size());
  EXPECT_TRUE(gt.front().isApprox(Eigen::Isometry3d::Identity(), 1e-12));
  // Ground truth back in the velodyne convention equals the simulated motion.
  const auto velo = seq.ground_truth_velo();
  ASSERT_TRUE(velo.has_value());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const Eigen::Isometry3d expected = poses.front().inverse() * poses[i];
    EXPECT_TRUE((*velo)[i].isApprox(expected, 1e-9)) << i;
  }
  // The camera-convention ground truth moves forward along camera z (KITTI: z forward).
  EXPECT_GT(gt.back().translation().z(), 3.0);
}

TEST(SimFleet, VehiclesShareStreetsAndWriteOwnFolders) {
  const auto path = sim::builtin_trajectory("loop");
  sim::FleetOptions fo;
  fo.vehicles = 3;
  const auto fleet = sim::plan_fleet(path, 10, 40, fo);
  ASSERT_EQ(fleet.size(), 3u);
  for (const auto& v : fleet) ASSERT_EQ(v.sensor_poses.size(), 40u);
  // Vehicle 1 drives the same stretch in reverse: its start is vehicle 0's end (plus the lane
  // offset) and it faces the other way.
  EXPECT_LT(
      (fleet[1].sensor_poses.front().translation() - fleet[0].sensor_poses.back().translation())
          .norm(),
      fo.lane_offset + 0.01);
  EXPECT_LT(fleet[1].sensor_poses.front().linear().col(0).dot(
                fleet[0].sensor_poses.back().linear().col(0)),
            -0.99);
  // Every pair of vehicles has frames within 5 m of each other (overlapping streets).
  for (std::size_t a = 0; a < fleet.size(); ++a) {
    for (std::size_t b = a + 1; b < fleet.size(); ++b) {
      std::size_t close = 0;
      for (const auto& pa : fleet[a].sensor_poses) {
        for (const auto& pb : fleet[b].sensor_poses) {
          if ((pa.translation() - pb.translation()).norm() < 5.0) {
            ++close;
            break;
          }
        }
      }
      EXPECT_GE(close, 10u) << a << " vs " << b;
    }
  }
  // One world for all vehicles; each writes its own KITTI folder.
  std::vector<std::vector<Eigen::Isometry3d>> paths{path};
  for (const auto& v : fleet) paths.push_back(v.sensor_poses);
  const sim::World world(paths, 5);
  const fs::path root = fresh_dir("fleet");
  for (std::size_t k = 0; k < fleet.size(); ++k) {
    sim::Raycaster rc(world);
    sim::SequenceWriteOptions opt;
    opt.model = sim::LidarModel::vlp16();
    opt.velo_to_cam = sim::kitti_default_velo_to_cam();
    const std::vector<Eigen::Isometry3d> few(fleet[k].sensor_poses.begin(),
                                             fleet[k].sensor_poses.begin() + 3);
    sim::write_sequence((root / ("vehicle_0" + std::to_string(k))).string(), rc, few, opt);
  }
  for (std::size_t k = 0; k < fleet.size(); ++k) {
    const io::ScanSequence seq((root / ("vehicle_0" + std::to_string(k))).string());
    EXPECT_EQ(seq.size(), 3u);
    EXPECT_TRUE(seq.ground_truth_cam().has_value());
  }
}

// Registration of the two real KITTI scans of ../shared/data/kitti/seq00_frames_xyz.
//
// On this pair the KITTI ground truth (0.859 m forward) disagrees with established methods:
// KISS-ICP and small_gicp both converge to about 0.69-0.70 m and return there when started at
// the ground truth. The test therefore requires agreement with that consensus within 5 cm and
// 0.15 deg, with the ground truth only within 0.25 m and 0.3 deg, and the 0->1 and 1->0
// registrations to be inverse to each other. Nothing is tuned towards this pair's ground truth.

#include "litamin2/core/correspondence_search.hpp"
#include "litamin2/core/registration.hpp"
#include "litamin2/core/scan_registration.hpp"
#include "litamin2/core/voxel_map.hpp"
#include "litamin2/core/voxelizer.hpp"
#include "litamin2/io/kitti_bin.hpp"
#include "litamin2/io/kitti_calib.hpp"
#include "litamin2/io/trajectory.hpp"
#include "support/register_clouds.hpp"

#include <gtest/gtest.h>

#include <filesystem>

namespace litamin2 {
namespace {

const std::string kData = LITAMIN2_SHARED_DATA_DIR "/kitti";

struct PoseError {
  double translation_m;
  double rotation_deg;
};

PoseError difference(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  const Eigen::Isometry3d delta = a.inverse() * b;
  return {delta.translation().norm(), Eigen::AngleAxisd(delta.linear()).angle() * 180.0 / M_PI};
}

Eigen::Isometry3d kiss_icp_consensus() {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topRows<3>() << 0.999995, -0.00288014, -0.000959547, 0.696571, 0.00287869, 0.999995,
      -0.00151635, 0.00810123, 0.000963909, 0.00151358, 0.999998, 0.0178178;
  return Eigen::Isometry3d(m);
}

/// Pose of `source` scan in the frame of `target` scan.
Eigen::Isometry3d register_pair(const PointCloud& target, const PointCloud& source, CostMode mode,
                                CorrespondenceMethod method = CorrespondenceMethod::kVoxel27,
                                const Eigen::Isometry3d& initial = Eigen::Isometry3d::Identity()) {
  RegistrationConfig config;
  config.mode = mode;
  config.correspondence = method;
  const RegistrationResult result = testing::register_clouds(target, source, initial, config);
  EXPECT_TRUE(result.valid);
  EXPECT_TRUE(result.converged) << result.iterations << " iterations";
  return result.pose;
}

class KittiPairTest : public ::testing::TestWithParam<CostMode> {
 protected:
  void SetUp() override {
    if (!std::filesystem::exists(kData + "/seq00_frames_xyz/000000.bin")) {
      GTEST_SKIP() << "shared KITTI data not found at " << kData;
    }
    scan0_ = io::read_kitti_bin(kData + "/seq00_frames_xyz/000000.bin");
    scan1_ = io::read_kitti_bin(kData + "/seq00_frames_xyz/000001.bin");
    const auto poses = io::read_kitti_poses(kData + "/poses/00.txt");
    const Eigen::Isometry3d tr = io::read_kitti_velo_to_cam(kData + "/calib_Tr_velo_to_cam.txt", 0);
    ground_truth_ = io::cam_pose_to_velo(poses[0].inverse() * poses[1], tr);
  }
  PointCloud scan0_, scan1_;
  Eigen::Isometry3d ground_truth_;
};

TEST_P(KittiPairTest, AgreesWithEstablishedMethodsAndGroundTruth) {
  const Eigen::Isometry3d estimate = register_pair(scan0_, scan1_, GetParam());
  const PoseError to_consensus = difference(estimate, kiss_icp_consensus());
  const PoseError to_truth = difference(estimate, ground_truth_);
  RecordProperty("translation_x", std::to_string(estimate.translation().x()));
  std::cout << "estimate t = " << estimate.translation().transpose()
            << "  vs consensus: " << to_consensus.translation_m << " m "
            << to_consensus.rotation_deg << " deg; vs ground truth: " << to_truth.translation_m
            << " m " << to_truth.rotation_deg << " deg\n";
  EXPECT_LT(to_consensus.translation_m, 0.05);
  EXPECT_LT(to_consensus.rotation_deg, 0.15);
  EXPECT_LT(to_truth.translation_m, 0.25);
  EXPECT_LT(to_truth.rotation_deg, 0.3);
}

TEST_P(KittiPairTest, ForwardAndBackwardAreInverse) {
  const Eigen::Isometry3d forward = register_pair(scan0_, scan1_, GetParam());
  const Eigen::Isometry3d backward = register_pair(scan1_, scan0_, GetParam());
  const PoseError loop = difference(forward * backward, Eigen::Isometry3d::Identity());
  std::cout << "0->1 * 1->0: " << loop.translation_m << " m " << loop.rotation_deg << " deg\n";
  EXPECT_LT(loop.translation_m, 0.01);
  EXPECT_LT(loop.rotation_deg, 0.05);
}

TEST_P(KittiPairTest, StartedAtGroundTruthReturnsToConsensus) {
  const Eigen::Isometry3d estimate =
      register_pair(scan0_, scan1_, GetParam(), CorrespondenceMethod::kVoxel27, ground_truth_);
  EXPECT_LT(difference(estimate, kiss_icp_consensus()).translation_m, 0.05);
}

TEST_P(KittiPairTest, KdTreeAndVoxelLookupGiveTheSamePose) {
  const Eigen::Isometry3d voxel = register_pair(scan0_, scan1_, GetParam());
  const Eigen::Isometry3d kdtree =
      register_pair(scan0_, scan1_, GetParam(), CorrespondenceMethod::kKdTree);
  const PoseError d = difference(voxel, kdtree);
  EXPECT_LT(d.translation_m, 1e-6);
  EXPECT_LT(d.rotation_deg, 1e-5);
}

INSTANTIATE_TEST_SUITE_P(Modes, KittiPairTest, ::testing::Values(CostMode::kIcp, CostMode::kIcpCov),
                         [](const auto& info) {
                           return info.param == CostMode::kIcp ? "Icp" : "IcpCov";
                         });

}  // namespace
}  // namespace litamin2

// A tilted sensor mount: the rotation, its validation, and a written sequence whose calibration
// carries the tilt so that its ground truth still holds for the tilted sensor.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "litamin2/io/kitti_sequence.hpp"
#include "litamin2/sim/builtin_trajectory.hpp"
#include "litamin2/sim/sensor_mount.hpp"
#include "litamin2/sim/sequence_writer.hpp"
#include "litamin2/sim/world.hpp"

namespace sim = litamin2::sim;
namespace io = litamin2::io;
namespace fs = std::filesystem;

TEST(SimSensorMount, RotationAndValidation) {
  sim::SensorMount m;
  EXPECT_TRUE(m.is_identity());
  EXPECT_TRUE(m.rotation().isApprox(Eigen::Matrix3d::Identity()));
  m.pitch_deg = 2.0;
  EXPECT_FALSE(m.is_identity());
  // Positive pitch turns the sensor's x axis downwards in the vehicle frame.
  const Eigen::Vector3d x = m.rotation() * Eigen::Vector3d::UnitX();
  EXPECT_NEAR(x.z(), -std::sin(2.0 * M_PI / 180.0), 1e-12);
  m.roll_deg = 45.0;
  EXPECT_THROW(m.validate(), std::invalid_argument);
  m.roll_deg = std::nan("");
  EXPECT_THROW(m.validate(), std::invalid_argument);
}

// The ground seen by a sensor pitched 2 degrees: its plane in the sensor frame is tilted by
// 2 degrees; calib.txt's Tr includes the tilt, and the ground truth of the tilted sensor
// (Tr'^-1 P Tr') is the vehicle's motion seen in the tilted frame.
TEST(SimSensorMount, TiltShowsInTheScanAndTheCalibration) {
  const auto path = sim::builtin_trajectory("loop");
  const std::vector<Eigen::Isometry3d> poses(path.begin() + 10, path.begin() + 14);
  const sim::World world(path, 2, sim::WorldOptions::ground_only());
  sim::Raycaster rc(world);
  sim::SequenceWriteOptions opt;
  opt.model = sim::LidarModel::vlp16();
  opt.model.range_noise_sigma = 0.0;
  opt.velo_to_cam = sim::kitti_default_velo_to_cam();
  opt.rig.mount.pitch_deg = 2.0;
  const fs::path dir = fs::path(LITAMIN2_BINARY_DIR) / "sim_test_output" / "tilted";
  fs::remove_all(dir);
  double max_slope = 0;
  opt.on_scan = [&](std::size_t, const litamin2::PointCloud& c) {
    // Ground points ahead and behind at 8-12 m: slope of z along x.
    double sa = 0, na = 0, sb = 0, nb = 0;
    for (const auto& p : c.points) {
      const double h = std::hypot(p.x(), p.y());
      if (h < 8 || h > 12 || std::abs(p.y()) > 2) continue;
      (p.x() > 0 ? sa : sb) += p.z();
      (p.x() > 0 ? na : nb) += 1;
    }
    ASSERT_GT(na, 0);
    ASSERT_GT(nb, 0);
    max_slope = std::max(max_slope, (sa / na - sb / nb) / 20.0);
  };
  sim::write_sequence(dir.string(), rc, poses, opt);
  EXPECT_NEAR(std::atan(max_slope) * 180.0 / M_PI, 2.0, 0.3);  // ground rises ahead

  const io::ScanSequence seq(dir.string());
  ASSERT_TRUE(seq.velo_to_cam().has_value());
  const Eigen::Isometry3d M(opt.rig.mount.rotation());
  EXPECT_TRUE(seq.velo_to_cam()->isApprox(opt.velo_to_cam * M, 1e-9));
  const auto gt = seq.ground_truth_velo();
  ASSERT_TRUE(gt.has_value());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const Eigen::Isometry3d want = (poses[0] * M).inverse() * (poses[i] * M);
    EXPECT_TRUE((*gt)[i].isApprox(want, 1e-6)) << i;
  }
}

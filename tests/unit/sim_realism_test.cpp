// The "street" realism preset: it changes what it says, the same seed writes the same bytes,
// and with sweep motion the PCD scans carry a per-point time field.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "litamin2/io/pcd.hpp"
#include "litamin2/sim/builtin_trajectory.hpp"
#include "litamin2/sim/frame_selection.hpp"
#include "litamin2/sim/realism.hpp"
#include "litamin2/sim/sequence_writer.hpp"
#include "litamin2/sim/traffic.hpp"
#include "litamin2/sim/world.hpp"

namespace sim = litamin2::sim;
namespace io = litamin2::io;
namespace fs = std::filesystem;

namespace {

std::string read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

/// Writes 8 frames of the built-in loop with the street preset into `name`.
fs::path write_street(const std::string& name, std::uint64_t seed) {
  const auto path = sim::builtin_trajectory("loop");
  const std::vector<Eigen::Isometry3d> poses(path.begin() + 50, path.begin() + 58);
  sim::RealismSettings s;
  s.model = sim::LidarModel::vlp16();
  sim::apply_realism("street", s);
  s.world.sensor_height = s.model.mount_height;
  const sim::World world(path, seed, s.world);
  const sim::Traffic traffic(poses, 0.1, world, seed, s.traffic);
  sim::Raycaster rc(world);
  sim::SequenceWriteOptions opt;
  opt.model = s.model;
  opt.rig = s.rig;
  opt.traffic = &traffic;
  opt.seed = seed;
  opt.write_pcd = true;
  opt.frames = sim::select_frames(poses.size(), s.drops, seed);
  opt.velo_to_cam = sim::kitti_default_velo_to_cam();
  const fs::path dir = fs::path(LITAMIN2_BINARY_DIR) / "sim_test_output" / name;
  fs::remove_all(dir);
  sim::write_sequence(dir.string(), rc, poses, opt);
  return dir;
}

}  // namespace

TEST(SimRealism, NoneChangesNothingStreetChangesTheRig) {
  sim::RealismSettings s;
  s.model = sim::LidarModel::vlp16();
  sim::apply_realism("none", s);
  EXPECT_FALSE(s.rig.sweep.motion);
  EXPECT_TRUE(s.rig.body.empty());
  EXPECT_TRUE(s.rig.mount.is_identity());
  EXPECT_FALSE(s.traffic.any());
  EXPECT_EQ(s.drops.probability, 0.0);
  EXPECT_EQ(s.world.ground_bump_amplitude, 0.0);
  sim::apply_realism("street", s);
  EXPECT_TRUE(s.rig.sweep.motion);
  EXPECT_EQ(s.rig.sweep.start_azimuth_deg, 180.0);
  EXPECT_TRUE(s.rig.sweep.clockwise);
  EXPECT_FALSE(s.rig.body.empty());
  EXPECT_FALSE(s.rig.mount.is_identity());
  EXPECT_TRUE(s.traffic.any());
  EXPECT_GT(s.drops.probability, 0.0);
  EXPECT_NO_THROW(s.rig.validate());
  EXPECT_THROW(sim::apply_realism("city", s), std::invalid_argument);
}

TEST(SimRealism, SameSeedSameBytesAndPcdWithTime) {
  const fs::path a = write_street("street_a", 7), b = write_street("street_b", 7);
  std::size_t files = 0;
  for (const auto& e : fs::recursive_directory_iterator(a)) {
    if (!e.is_regular_file()) continue;
    const fs::path other = b / fs::relative(e.path(), a);
    ASSERT_TRUE(fs::exists(other)) << other;
    EXPECT_EQ(read_bytes(e.path()), read_bytes(other)) << e.path();
    ++files;
  }
  EXPECT_GT(files, 8u);
  const fs::path c = write_street("street_c", 8);
  EXPECT_NE(read_bytes(a / "velodyne" / "000001.bin"), read_bytes(c / "velodyne" / "000001.bin"));

  // The PCD holds the .bin's points and, per point, t in [0, 0.1) s and the ring.
  const fs::path pcd = a / "pcd" / "000001.pcd";
  const auto cloud = io::read_pcd(pcd.string());
  const std::string bin = read_bytes(a / "velodyne" / "000001.bin");
  ASSERT_EQ(bin.size(), cloud.size() * 16);
  for (std::size_t i = 0; i < cloud.size(); i += 101) {
    float xyz[3];
    std::memcpy(xyz, bin.data() + 16 * i, sizeof(xyz));
    EXPECT_EQ(xyz[0], cloud.points[i].x());
    EXPECT_EQ(xyz[2], cloud.points[i].z());
  }
  const std::string bytes = read_bytes(pcd);
  ASSERT_NE(bytes.find("FIELDS x y z intensity t ring\nSIZE 4 4 4 4 4 2\nTYPE F F F F F U\n"),
            std::string::npos);
  const std::size_t data = bytes.find("DATA binary\n") + 12;
  const std::size_t stride = 22;
  ASSERT_EQ(bytes.size() - data, cloud.size() * stride);
  float t_prev = 0.0f, t_last = 0.0f;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    float t;
    std::uint16_t ring;
    std::memcpy(&t, bytes.data() + data + i * stride + 16, 4);
    std::memcpy(&ring, bytes.data() + data + i * stride + 20, 2);
    ASSERT_GE(t, t_prev);  // firing order
    ASSERT_LT(t, 0.1f);
    ASSERT_LT(ring, 16);
    t_prev = t_last = t;
  }
  EXPECT_GT(t_last, 0.09f);
}

// World generation: determinism, road clearance, ground height, memory-bounded tiles, speed.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <map>

#include "litamin2/io/kitti_calib.hpp"
#include "litamin2/io/trajectory.hpp"
#include "litamin2/sim/builtin_trajectory.hpp"
#include "litamin2/sim/ground_clearance.hpp"
#include "litamin2/sim/raycaster.hpp"
#include "litamin2/sim/world.hpp"
#include "support/climb_in_place.hpp"

namespace sim = litamin2::sim;
namespace io = litamin2::io;

TEST(SimWorld, DeterministicLayoutAndTiles) {
  const auto path = sim::builtin_trajectory("loop");
  const sim::World a(path, 17), b(path, 17), c(path, 18);
  ASSERT_EQ(a.objects().size(), b.objects().size());
  ASSERT_GT(a.objects().size(), 50u);
  for (std::size_t i = 0; i < a.objects().size(); ++i) {
    EXPECT_EQ(a.objects()[i].center, b.objects()[i].center);
    EXPECT_EQ(a.objects()[i].seed, b.objects()[i].seed);
  }
  const auto key = a.tile_of(path[100].translation().head<2>());
  const auto ma = a.build_tile(key), mb = b.build_tile(key), mc = c.build_tile(key);
  ASSERT_EQ(ma.vertices.size(), mb.vertices.size());
  EXPECT_TRUE(std::equal(ma.vertices.begin(), ma.vertices.end(), mb.vertices.begin()));
  EXPECT_FALSE(ma.vertices.size() == mc.vertices.size() &&
               std::equal(ma.vertices.begin(), ma.vertices.end(), mc.vertices.begin()));
}

TEST(SimWorld, RoadIsClearAndGroundIsBelowTheSensor) {
  const auto path = sim::builtin_trajectory("loop");
  const sim::World w(path, 21);
  std::map<sim::ObjectKind, int> kinds;
  for (const auto& o : w.objects()) {
    ++kinds[o.kind];
    const double d = w.distance_to_path(o.center.x(), o.center.y());
    if (o.kind == sim::ObjectKind::kCar) {
      EXPECT_GT(d, 3.0);
    } else {
      EXPECT_GT(d, w.options().road_half_width) << sim::object_kind_name(o.kind);
    }
  }
  EXPECT_GE(kinds.size(), 5u);  // a mix of object kinds
  for (std::size_t i = 0; i < path.size(); i += 25) {
    const Eigen::Vector3d p = path[i].translation();
    EXPECT_NEAR(w.ground_height(p.x(), p.y()), p.z() - 1.73, 0.08) << "frame " << i;
    // Nothing blocks the road just ahead of the sensor.
    sim::Raycaster rc(w);
    rc.prepare(p, 20.0);
    const Eigen::Vector3d fwd = path[i].linear().col(0);
    const auto hit = rc.cast(p, fwd, 3.0);
    EXPECT_FALSE(hit.has_value()) << "frame " << i;
  }
}

TEST(SimWorld, Kitti00WorldBuildsFastAndTileCacheIsBounded) {
  const std::string poses = std::string(LITAMIN2_SHARED_DATA_DIR) + "/kitti/poses/00.txt";
  if (!std::ifstream(poses)) GTEST_SKIP() << "no shared data at " << poses;
  const auto velo =
      io::cam_to_velo_trajectory(io::read_kitti_poses(poses), sim::kitti_default_velo_to_cam());
  ASSERT_EQ(velo.size(), 4541u);
  const auto t0 = std::chrono::steady_clock::now();
  const sim::World w(velo, 1);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_LT(s, 10.0);
  EXPECT_GT(w.objects().size(), 1000u);
  // Visiting far-apart places keeps at most max_cached_tiles tiles alive.
  sim::RaycasterOptions ro;
  ro.max_cached_tiles = 60;
  sim::Raycaster rc(w, ro);
  for (std::size_t i = 0; i < velo.size(); i += 1500) {
    rc.prepare(velo[i].translation(), 120.0);
    EXPECT_LE(rc.cached_tiles(), std::max<std::size_t>(60, rc.active_tiles()));
    EXPECT_GT(rc.active_triangles(), 10000u);
  }
}

TEST(SimWorld, GroundClearanceFlagsAClimbInPlace) {
  // The built-in loop rides on its road; a path that rises 8 m while it moves 8 m forward (a
  // ground truth's height drift at a near standstill) cannot have a road under every pose.
  const auto loop = sim::builtin_trajectory("loop");
  const sim::World on_road(loop, 3);
  const sim::GroundClearance fine =
      sim::check_ground_clearance(on_road, loop, on_road.options().sensor_height, 0.5);
  EXPECT_EQ(fine.poses_off, 0u);
  EXPECT_LT(fine.worst_m, 0.5);

  const std::vector<Eigen::Isometry3d> climb = litamin2::testing::climb_in_place();
  const sim::World world(climb, 3);
  const sim::GroundClearance c =
      sim::check_ground_clearance(world, climb, world.options().sensor_height, 0.5);
  EXPECT_GT(c.poses_off, 10u);
  EXPECT_GE(c.first_off, 40u);  // the flagged stretch is around the climb, not the flat ends
  EXPECT_LE(c.last_off, 120u);
  EXPECT_GT(c.worst_m, 1.5);
}

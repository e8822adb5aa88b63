// Moving actors: deterministic placement, motion along the road, and that the ray caster sees
// them where they are at each sweep.
#include <gtest/gtest.h>

#include <stdexcept>

#include "litamin2/sim/builtin_trajectory.hpp"
#include "litamin2/sim/raycaster.hpp"
#include "litamin2/sim/traffic.hpp"
#include "litamin2/sim/world.hpp"

namespace sim = litamin2::sim;

TEST(SimTraffic, ActorsFollowTheRoad) {
  const auto path = sim::builtin_trajectory("loop");
  const sim::World world(path, 4);
  sim::TrafficOptions opt;
  opt.lead_vehicle = true;
  opt.oncoming_per_km = 10;
  opt.pedestrians_per_km = 20;
  const sim::Traffic traffic(path, 0.1, world, 8, opt);
  ASSERT_GT(traffic.size(), 5u);
  EXPECT_EQ(traffic.kind(0), sim::ActorKind::kLeadVehicle);
  std::size_t oncoming = 0, pedestrians = 0;
  for (std::size_t i = 0; i < traffic.size(); ++i) {
    EXPECT_FALSE(traffic.mesh(i).empty());
    oncoming += traffic.kind(i) == sim::ActorKind::kOncomingVehicle;
    pedestrians += traffic.kind(i) == sim::ActorKind::kPedestrian;
  }
  EXPECT_GT(oncoming, 0u);
  EXPECT_GT(pedestrians, 0u);
  // The lead car stays ahead of the ego vehicle in its lane, 5-60 m away.
  for (double t : {0.0, 5.0, 12.3, 30.0}) {
    const std::size_t f = static_cast<std::size_t>(t / 0.1);
    const Eigen::Isometry3d ego = path[f];
    const Eigen::Vector3d lead = ego.inverse() * traffic.pose(0, t).translation();
    EXPECT_GT(lead.x(), 5.0) << t;
    EXPECT_LT(lead.head<2>().norm(), 60.0) << t;
  }
  // Actors move; the same seed places them identically.
  const sim::Traffic again(path, 0.1, world, 8, opt);
  for (std::size_t i = 0; i < traffic.size(); ++i) {
    EXPECT_TRUE(traffic.pose(i, 3.0).isApprox(again.pose(i, 3.0)));
    const double moved =
        (traffic.pose(i, 3.0).translation() - traffic.pose(i, 4.0).translation()).head<2>().norm();
    EXPECT_GT(moved, 0.5) << i;  // >= 0.8 m/s
  }
  opt.oncoming_per_km = -1;
  EXPECT_THROW(sim::Traffic(path, 0.1, world, 8, opt), std::invalid_argument);
}

TEST(SimTraffic, RaycasterSeesTheActorsWhereTheyAre) {
  const auto path = sim::builtin_trajectory("loop");
  const sim::World world(path, 4, sim::WorldOptions::ground_only());
  sim::TrafficOptions opt;
  opt.lead_vehicle = true;
  const sim::Traffic traffic(path, 0.1, world, 8, opt);
  sim::Raycaster rc(world);
  const sim::LidarModel model = sim::LidarModel::vlp16();
  auto actor_points = [&](double t, std::size_t frame) {
    sim::SweepRequest r;
    r.start = r.end = path[frame];
    r.start_time = t;
    r.traffic = &traffic;
    const auto scan = rc.scan(r, model, sim::SensorRig{}, 3);
    // Points well above the ground (the world is ground only): the lead car.
    std::vector<Eigen::Vector3d> out;
    for (const auto& p : scan.cloud.points) {
      const Eigen::Vector3d w = path[frame] * p.cast<double>();
      if (w.z() > world.ground_height(w.x(), w.y()) + 0.4) out.push_back(w);
    }
    return out;
  };
  const auto at10 = actor_points(10.0, 100);
  ASSERT_GT(at10.size(), 20u);
  const Eigen::Vector3d car = traffic.pose(0, 10.0).translation();
  for (const auto& p : at10) EXPECT_LT((p - car).head<2>().norm(), 3.5);
  // A second later (same vehicle pose) the car has moved on, and so have its points.
  const auto at11 = actor_points(11.0, 100);
  ASSERT_GT(at11.size(), 10u);
  const Eigen::Vector3d car11 = traffic.pose(0, 11.0).translation();
  EXPECT_GT((car11 - car).head<2>().norm(), 3.0);
  for (const auto& p : at11) EXPECT_LT((p - car11).head<2>().norm(), 3.5);
  // Without traffic there is nothing above the ground.
  sim::SweepRequest r;
  r.start = r.end = path[100];
  EXPECT_EQ(rc.scan(r, model, sim::SensorRig{}, 3).cloud.size(),
            rc.scan(path[100], model, 3).size());
}

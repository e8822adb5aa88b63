// Motion within a sweep: the continuous trajectory, the sweep's column timing, and that a sweep
// cast with known motion puts each point where the sensor was at the point's time.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <stdexcept>

#include "litamin2/sim/builtin_trajectory.hpp"
#include "litamin2/sim/continuous_trajectory.hpp"
#include "litamin2/sim/raycaster.hpp"
#include "litamin2/sim/sweep.hpp"
#include "litamin2/sim/world.hpp"

namespace sim = litamin2::sim;

namespace {

Eigen::Isometry3d pose(double x, double y, double yaw_deg) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()).matrix();
  T.translation() = Eigen::Vector3d(x, y, 0.0);
  return T;
}

double yaw_deg(const Eigen::Isometry3d& T) {
  return std::atan2(T.linear()(1, 0), T.linear()(0, 0)) * 180.0 / M_PI;
}

}  // namespace

TEST(SimContinuousTrajectory, InterpolatesExactlyAtSamplesAndLinearlyBetween) {
  const sim::ContinuousTrajectory traj({pose(0, 0, 0), pose(1, 0, 10), pose(3, 0, 30)}, 0.1);
  EXPECT_TRUE(traj.pose_at(0.1).isApprox(pose(1, 0, 10), 1e-12));
  EXPECT_TRUE(traj.pose_at(0.2).isApprox(pose(3, 0, 30), 1e-12));
  const Eigen::Isometry3d mid = traj.pose_at(0.15);
  EXPECT_NEAR(mid.translation().x(), 2.0, 1e-9);
  EXPECT_NEAR(yaw_deg(mid), 20.0, 1e-9);
  // Constant velocity beyond both ends.
  EXPECT_NEAR(traj.pose_at(0.25).translation().x(), 4.0, 1e-9);
  EXPECT_NEAR(yaw_deg(traj.pose_at(0.25)), 40.0, 1e-9);
  EXPECT_NEAR(traj.pose_at(-0.05).translation().x(), -0.5, 1e-9);
  EXPECT_NEAR(yaw_deg(traj.pose_at(-0.05)), -5.0, 1e-9);
}

TEST(SimContinuousTrajectory, RejectsBadTimes) {
  EXPECT_THROW(sim::ContinuousTrajectory({}, 0.1), std::invalid_argument);
  EXPECT_THROW(sim::ContinuousTrajectory({pose(0, 0, 0), pose(1, 0, 0)}, {0.0, 0.0}),
               std::invalid_argument);
  EXPECT_THROW(sim::ContinuousTrajectory({pose(0, 0, 0)}, {0.0, 1.0}), std::invalid_argument);
  EXPECT_THROW(sim::ContinuousTrajectory({pose(0, 0, 0), pose(1, 0, 0)}, 0.0),
               std::invalid_argument);
}

TEST(SimSweep, ColumnAzimuthAndTime) {
  sim::SweepOptions def;
  EXPECT_TRUE(def.is_default_layout());
  EXPECT_DOUBLE_EQ(def.column_azimuth(450, 1800), 2.0 * M_PI * 450 / 1800);
  sim::SweepOptions velodyne;
  velodyne.start_azimuth_deg = 180.0;
  velodyne.clockwise = true;
  EXPECT_FALSE(velodyne.is_default_layout());
  EXPECT_NEAR(velodyne.column_azimuth(0, 1800), M_PI, 1e-12);
  EXPECT_NEAR(velodyne.column_azimuth(450, 1800), M_PI / 2, 1e-12);  // a quarter turn clockwise
  EXPECT_NEAR(velodyne.column_time(900, 1800), 0.05, 1e-12);
  velodyne.duration = 0.0;
  EXPECT_THROW(velodyne.validate(), std::invalid_argument);
  velodyne.duration = 0.1;
  velodyne.start_azimuth_deg = 400.0;
  EXPECT_THROW(velodyne.validate(), std::invalid_argument);
}

// Each point of a sweep with motion is where a static scan from the pose at the point's time
// puts it (same column, beam and noise), in the sensor frame of that time: raw, as drivers
// publish it. Carried into the sweep-start frame (what a deskew does) it moves by the motion.
TEST(SimSweep, EachPointIsCastFromThePoseAtItsTime) {
  const auto path = sim::builtin_trajectory("loop");
  const sim::World world(path, 3);
  sim::Raycaster rc(world, {1000, false, false});
  sim::LidarModel model = sim::LidarModel::vlp16();
  sim::SensorRig moving;
  moving.sweep.motion = true;
  moving.sweep.start_azimuth_deg = 180.0;
  moving.sweep.clockwise = true;
  sim::SensorRig still = moving;
  still.sweep.motion = false;

  sim::SweepRequest request;
  request.start = path[60];
  // 1.5 m forward and 4 degrees of yaw within the sweep: a fast turn.
  request.end = path[60] * pose(1.5, 0.1, 4.0);
  const auto sweep = rc.scan(request, model, moving, 17);
  ASSERT_EQ(sweep.cloud.size(), sweep.times.size());
  ASSERT_EQ(sweep.cloud.size(), sweep.rings.size());
  ASSERT_GT(sweep.cloud.size(), 10000u);
  for (std::size_t i = 1; i < sweep.times.size(); ++i) {
    ASSERT_LE(sweep.times[i - 1], sweep.times[i]);  // ordered by firing time
  }
  EXPECT_GT(sweep.times.back(), 0.099f);

  // Columns at a few times: static scans from the interpolated pose.
  const int steps = model.azimuth_steps;
  int compared = 0;
  for (int column : {0, 301, 900, 1333, 1799}) {
    const double s = static_cast<double>(column) / steps;
    sim::SweepRequest at;
    at.start = at.end = sim::interpolate_pose(request.start, request.end, s);
    const auto still_scan = rc.scan(at, model, still, 17);
    const float t = static_cast<float>(moving.sweep.column_time(column, steps));
    std::map<int, Eigen::Vector3f> expected;  // ring -> point of this column
    for (std::size_t i = 0; i < still_scan.cloud.size(); ++i) {
      if (still_scan.times[i] == t) expected[still_scan.rings[i]] = still_scan.cloud.points[i];
    }
    const Eigen::Isometry3d to_start = request.start.inverse() * at.start;
    for (std::size_t i = 0; i < sweep.cloud.size(); ++i) {
      if (sweep.times[i] != t) continue;
      const auto it = expected.find(sweep.rings[i]);
      ASSERT_NE(it, expected.end()) << "column " << column << " ring " << sweep.rings[i];
      const Eigen::Vector3d raw = sweep.cloud.points[i].cast<double>();
      EXPECT_LT((raw - it->second.cast<double>()).norm(), 2e-3)
          << "column " << column << " ring " << sweep.rings[i];
      // Deskewed, the point moves by the sensor's motion up to its time: not at all in the
      // first column, more than a metre in the last (1.5 m and 4 deg within the sweep).
      const double moved = (to_start * raw - raw).norm();
      if (column == 0) {
        EXPECT_LT(moved, 1e-9);
      }
      if (column == 1799) {
        EXPECT_GT(moved, 1.0);
      }
      ++compared;
    }
  }
  EXPECT_GT(compared, 40);
}

// A moving sweep of a flat ground: each raw point is a ray of its column from the sensor at
// its time, so its azimuth in the sensor frame is the column's, however far the sensor moved;
// carried into the sweep-start frame it is displaced by the motion up to its time.
TEST(SimSweep, MotionShiftsLateColumns) {
  std::vector<Eigen::Isometry3d> path;
  for (int i = 0; i < 400; ++i) path.push_back(pose(i - 200.0, 0, 0));
  const sim::World world(path, 5, sim::WorldOptions::ground_only());
  sim::Raycaster rc(world);
  const sim::LidarModel model = sim::LidarModel::vlp16();
  sim::SensorRig rig;
  rig.sweep.motion = true;
  sim::SweepRequest request;
  request.start = path[200];
  request.end = path[200] * pose(2.0, 0, 0);  // 20 m/s
  const auto sweep = rc.scan(request, model, rig, 1);
  int checked = 0;
  for (std::size_t i = 0; i < sweep.cloud.size(); i += 97) {
    const double s = sweep.times[i] / rig.sweep.duration;
    const Eigen::Vector3d ray = sweep.cloud.points[i].cast<double>();
    double az = std::atan2(ray.y(), ray.x());
    if (az < 0) az += 2 * M_PI;
    const double expected = 2.0 * M_PI * s;
    EXPECT_NEAR(std::remainder(az - expected, 2 * M_PI), 0.0, 2e-3) << i;
    // Deskewed (sensor offset 2 m * s along x at that time) the point is off its column's ray
    // through the sweep-start origin by 2 m * s * |sin(azimuth)|: the distortion a deskew
    // removes.
    const double off_ray = [&](const Eigen::Vector3d& p) {
      return std::abs(p.x() * std::sin(expected) - p.y() * std::cos(expected));
    }(ray + Eigen::Vector3d(2.0 * s, 0, 0));
    EXPECT_NEAR(off_ray, 2.0 * s * std::abs(std::sin(expected)), 0.02) << i;
    ++checked;
  }
  EXPECT_GT(checked, 50);
}

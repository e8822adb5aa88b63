// Deskew (core/deskew.hpp, Tracker::process with a SweepTiming): SE(3) exp/log, a sweep taken
// with known motion becomes the static scan, azimuth times, determinism, invalid input, and the
// tracker on sweeps with motion, with and without deskew.

#include "litamin2/core/deskew.hpp"
#include "litamin2/core/scan_filter.hpp"
#include "litamin2/core/so3.hpp"
#include "litamin2/core/tracker.hpp"
#include "support/synthetic_scene.hpp"
#include "support/twists.hpp"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <cstring>
#include <random>

namespace litamin2 {
namespace {

using testing::angle_deg;
using testing::twist;

TEST(Deskew, ExpAndLogAreInverse) {
  for (const Twist& xi :
       {twist(0.0, 0.0, 0.0, 25.0, 0.0, 0.0), twist(0.1, -0.2, 0.6, 12.0, 1.0, -0.5),
        twist(1e-9, 0.0, 2e-9, 3.0, 0.0, 0.0), twist(0.0, 0.0, 3.0, 0.0, 2.0, 0.0)}) {
    const Eigen::Isometry3d m = motion_after(xi, 0.1);
    const Twist back = twist_from_motion(m, 0.1);
    EXPECT_LT((back.angular - xi.angular).norm(), 1e-9);
    EXPECT_LT((back.linear - xi.linear).norm(), 1e-9);
  }
  // A screw: a constant yaw rate and forward speed drive an arc, Exp(t xi) = Exp(xi)^t.
  const Twist car = twist(0.0, 0.0, 0.5, 20.0, 0.0, 0.0);
  const Eigen::Isometry3d half = motion_after(car, 0.05);
  const Eigen::Isometry3d whole = motion_after(car, 0.1);
  EXPECT_LT(((half * half).matrix() - whole.matrix()).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_NEAR(angle_deg(whole.linear()), 0.05 * 180.0 / M_PI, 1e-9);
  // The chord of an arc of length 2 m with a turn of 0.05 rad.
  EXPECT_NEAR(whole.translation().norm(), 2.0 * std::sin(0.025) / 0.025, 1e-9);
  EXPECT_THROW(twist_from_motion(whole, 0.0), std::invalid_argument);
}

/// A static scan (the sensor frame at the stamp) and its points as a moving sensor measures
/// them: point i at time times[i] is seen from the pose Exp(t xi), so raw = Exp(t xi)^-1 p.
struct Sweep {
  PointCloud still;
  PointCloud raw;
};

Sweep sweep(const Twist& xi, double period, unsigned seed, double t0 = 0.0) {
  Sweep s;
  s.still = testing::synthetic_scene(seed, 20000);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  s.raw = s.still;
  s.raw.intensities.assign(s.still.size(), 0.5f);
  s.raw.times.resize(s.still.size());
  for (std::size_t i = 0; i < s.still.size(); ++i) {
    const float t = static_cast<float>(t0 + period * u(rng));
    s.raw.times[i] = t;
    s.raw.points[i] =
        (motion_after(xi, t).inverse() * s.still.points[i].cast<double>()).cast<float>();
  }
  return s;
}

TEST(Deskew, SweepWithKnownMotionBecomesTheStaticScan) {
  // Highway speed with a turn, roll and pitch, and a sweep whose stamp is its end (times < 0).
  for (const double t0 : {0.0, -0.1}) {
    const Twist xi = twist(0.02, -0.03, 0.4, 33.0, 0.5, 0.2);
    const Sweep s = sweep(xi, 0.1, 3, t0);
    double skew = 0.0;
    for (std::size_t i = 0; i < s.raw.size(); ++i)
      skew = std::max(skew, double((s.raw.points[i] - s.still.points[i]).norm()));
    EXPECT_GT(skew, 3.0);  // the raw sweep is far from the static scan
    PointCloud out;
    deskew(s.raw, xi, out);
    ASSERT_EQ(out.size(), s.still.size());
    EXPECT_FALSE(out.has_times());
    EXPECT_EQ(out.intensities, s.raw.intensities);
    double worst = 0.0;
    for (std::size_t i = 0; i < out.size(); ++i)
      worst = std::max(worst, double((out.points[i] - s.still.points[i]).norm()));
    EXPECT_LT(worst, 1e-4) << "stamp offset " << t0;  // float rounding at up to 100 m
  }
}

TEST(Deskew, ZeroTwistOrZeroTimesChangeNothing) {
  const Sweep s = sweep(twist(0.0, 0.0, 0.3, 10.0, 0.0, 0.0), 0.1, 5);
  PointCloud out;
  deskew(s.raw, Twist{}, out);
  EXPECT_EQ(out.points, s.raw.points);
  PointCloud at_stamp = s.raw;
  std::fill(at_stamp.times.begin(), at_stamp.times.end(), 0.0f);
  deskew(at_stamp, twist(0.0, 0.0, 0.3, 10.0, 0.0, 0.0), out);
  EXPECT_EQ(out.points, s.raw.points);
}

TEST(Deskew, SameBitsForAnyThreadCount) {
  Sweep s = sweep(twist(0.01, 0.0, 0.5, 20.0, 0.0, 0.0), 0.1, 9);
  // 120k points: several parallel chunks.
  const Sweep more = sweep(twist(0.01, 0.0, 0.5, 20.0, 0.0, 0.0), 0.1, 10);
  for (int k = 0; k < 5; ++k) {
    s.raw.points.insert(s.raw.points.end(), more.raw.points.begin(), more.raw.points.end());
    s.raw.times.insert(s.raw.times.end(), more.raw.times.begin(), more.raw.times.end());
  }
  s.raw.intensities.clear();
  PointCloud reference;
  tbb::task_arena(1).execute(
      [&] { deskew(s.raw, twist(0.01, 0.0, 0.5, 20.0, 0.0, 0.0), reference); });
  for (int threads : {2, 4}) {
    PointCloud out;
    tbb::task_arena(threads).execute(
        [&] { deskew(s.raw, twist(0.01, 0.0, 0.5, 20.0, 0.0, 0.0), out); });
    ASSERT_EQ(out.size(), reference.size());
    EXPECT_EQ(0, std::memcmp(out.points.data(), reference.points.data(),
                             out.size() * sizeof(Eigen::Vector3f)));
  }
}

TEST(Deskew, InvalidTimesAreRejected) {
  Sweep s = sweep(twist(0.0, 0.0, 0.1, 5.0, 0.0, 0.0), 0.1, 11);
  PointCloud out;
  PointCloud bad = s.raw;
  bad.times.pop_back();
  EXPECT_THROW(deskew(bad, Twist{}, out), std::invalid_argument);
  EXPECT_TRUE(point_times_error(bad).has_value());
  bad = s.raw;
  bad.times[7] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(deskew(bad, Twist{}, out), std::invalid_argument);
  EXPECT_TRUE(point_times_error(bad).has_value());
  bad.times[7] = 1.5f;  // a unit error: milliseconds read as seconds
  EXPECT_THROW(deskew(bad, Twist{}, out), std::invalid_argument);
  EXPECT_THROW(deskew(s.raw, Twist{}, const_cast<PointCloud&>(s.raw)), std::invalid_argument);
  EXPECT_FALSE(point_times_error(s.raw).has_value());
  EXPECT_FALSE(point_times_error(s.still).has_value());  // no times at all is valid
}

TEST(Deskew, TimesFromAzimuth) {
  PointCloud scan;
  for (double deg : {180.0, 179.0, 90.0, 0.0, -90.0, -179.0})
    scan.points.emplace_back(10.0f * std::cos(deg * M_PI / 180.0),
                             10.0f * std::sin(deg * M_PI / 180.0), 0.0f);
  AzimuthTiming velodyne;  // 0.1 s, starting behind, clockwise
  std::vector<float> times;
  times_from_azimuth(scan, velodyne, times);
  ASSERT_EQ(times.size(), scan.size());
  const double expected_cw[] = {0.0, 1.0 / 360, 0.25, 0.5, 0.75, 359.0 / 360};
  for (std::size_t i = 0; i < times.size(); ++i)
    EXPECT_NEAR(times[i], 0.1 * expected_cw[i], 1e-6) << i;
  AzimuthTiming ccw;
  ccw.clockwise = false;
  ccw.start_deg = 0.0;
  ccw.period_s = 0.05;
  times_from_azimuth(scan, ccw, times);
  const double expected_ccw[] = {0.5, 179.0 / 360, 0.25, 0.0, 0.75, 181.0 / 360};
  for (std::size_t i = 0; i < times.size(); ++i)
    EXPECT_NEAR(times[i], 0.05 * expected_ccw[i], 1e-6) << i;
}

TEST(Deskew, ConfigIsValidated) {
  DeskewConfig c;
  EXPECT_NO_THROW(validate(c));
  c.passes = 3;
  EXPECT_THROW(validate(c), ConfigError);
  c = DeskewConfig{};
  c.azimuth.period_s = 0.0;
  EXPECT_THROW(validate(c), ConfigError);
  c = DeskewConfig{};
  c.azimuth.start_deg = 400.0;
  EXPECT_THROW(validate(c), ConfigError);
  TrackerConfig tracker;
  tracker.deskew.passes = 0;
  try {
    validate(tracker);
    FAIL() << "passes 0 accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("deskew.passes"), std::string::npos) << e.what();
  }
}

// ---- the tracker on sweeps with motion ------------------------------------------------------

/// A drive at 25 m/s whose yaw rate changes (0 to 0.45 rad/s): the sensor's pose at time s is
/// pose(s); scan k is stamped at 0.1 k and sweeps [0.1 k, 0.1 k + 0.1). With `roll_rate` the
/// body also rolls at roll_rate sin(2 pi s) rad/s (a 1 Hz wobble of roll_rate / 2 pi rad).
struct Drive {
  static constexpr double kPeriod = 0.1;
  static Twist twist_at(double s, double roll_rate) {
    return twist(roll_rate * std::sin(2.0 * M_PI * s), 0.0, 0.45 * std::sin(0.8 * s), 25.0, 0.0,
                 0.0);
  }
  /// Integrates the twist in steps of 1 ms from (-35, -3) heading along x.
  static Eigen::Isometry3d pose(double s, double roll_rate = 0.0) {
    Eigen::Isometry3d p = testing::planar_pose(-35.0, -3.0, 0.0);
    const int steps = static_cast<int>(std::lround(s / 1e-3));
    for (int k = 0; k < steps; ++k)
      p = p * motion_after(twist_at((k + 0.5) * 1e-3, roll_rate), 1e-3);
    return p;
  }
};

/// Scan k as a moving sensor measures it: each world point keeps the time of its azimuth in a
/// clockwise sweep starting behind the sensor, and is seen from the pose at that time.
PointCloud moving_scan(int k, bool with_times, double roll_rate = 0.0) {
  const double stamp = k * Drive::kPeriod;
  const Eigen::Isometry3d at_stamp = Drive::pose(stamp, roll_rate);
  PointCloud scan =
      testing::transformed(testing::synthetic_scene(200 + k, 30000), at_stamp.inverse());
  std::vector<float> times;
  times_from_azimuth(scan, AzimuthTiming{}, times);
  // Poses within the sweep on a 1 ms grid (interpolation error well below the test's bounds).
  std::vector<Eigen::Isometry3d> within;
  for (int ms = 0; ms <= 100; ++ms)
    within.push_back(at_stamp.inverse() * Drive::pose(stamp + ms * 1e-3, roll_rate));
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const Eigen::Isometry3d& sensor = within[static_cast<std::size_t>(std::lround(times[i] * 1e3))];
    scan.points[i] = (sensor.inverse() * scan.points[i].cast<double>()).cast<float>();
    times[i] = static_cast<float>(std::lround(times[i] * 1e3) * 1e-3);
  }
  if (with_times) scan.times = times;
  return scan;
}

struct Errors {
  double mean_m = 0.0, max_m = 0.0, max_deg = 0.0;
  std::vector<Eigen::Isometry3d> poses;
};

Errors track(const std::vector<PointCloud>& scans, bool deskew, int passes,
             TimeSource source = TimeSource::kField, bool sweep_motion = false,
             double roll_rate = 0.0, double sweep_motion_min_speed = 0.0) {
  TrackerConfig config;
  config.deskew.enabled = deskew;
  config.deskew.passes = passes;
  config.deskew.sweep_motion.enabled = sweep_motion;
  config.deskew.sweep_motion.min_speed_mps = sweep_motion_min_speed;
  config.deskew.time_source = source;
  Tracker tracker(config);
  Errors e;
  const Eigen::Isometry3d origin = Drive::pose(0.0).inverse();
  for (std::size_t k = 0; k < scans.size(); ++k) {
    const FrameResult r =
        tracker.process(scans[k], SweepTiming{Stamp::from_seconds(k * Drive::kPeriod)});
    EXPECT_EQ(r.deskewed, deskew) << k;
    e.poses.push_back(r.pose);
    const Eigen::Isometry3d error =
        (origin * Drive::pose(k * Drive::kPeriod, roll_rate)).inverse() * r.pose;
    e.mean_m += error.translation().norm() / scans.size();
    e.max_m = std::max(e.max_m, error.translation().norm());
    e.max_deg = std::max(e.max_deg, angle_deg(error.linear()));
  }
  return e;
}

class DeskewTracker : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    for (int k = 0; k < 25; ++k) {
      scans_with_times().push_back(moving_scan(k, true));
      PointCloud bare = scans_with_times().back();
      bare.times.clear();
      scans_without_times().push_back(bare);
    }
  }
  static std::vector<PointCloud>& scans_with_times() {
    static std::vector<PointCloud> s;
    return s;
  }
  static std::vector<PointCloud>& scans_without_times() {
    static std::vector<PointCloud> s;
    return s;
  }
};

TEST_F(DeskewTracker, DeskewFollowsTheSensorAtTheStamp) {
  const Errors off = track(scans_with_times(), false, 2);
  const Errors one = track(scans_with_times(), true, 1);
  const Errors two = track(scans_with_times(), true, 2);
  std::printf(
      "pose error at the stamp over 25 sweeps at 25 m/s: off mean %.3f max %.3f m %.2f "
      "deg; 1 pass %.3f / %.3f m %.2f deg; 2 passes %.3f / %.3f m %.2f deg\n",
      off.mean_m, off.max_m, off.max_deg, one.mean_m, one.max_m, one.max_deg, two.mean_m, two.max_m,
      two.max_deg);
  EXPECT_LT(two.max_m, 0.15);
  EXPECT_LT(two.max_deg, 0.3);
  // One pass (the prediction only) is better on average but not on every frame: measured
  // mean 0.17 m, max 1.17 m / 4.9 deg (off: 0.39 / 1.13 m / 1.8 deg), so only the mean is bound.
  EXPECT_LT(two.mean_m, 0.5 * off.mean_m);
  EXPECT_LT(one.mean_m, 0.5 * off.mean_m);
}

TEST(DeskewTrackerWobble, TheMotionWithinTheSweepIsEstimatedWithThePose) {
  // The body rolls at 0.3 sin(2 pi s) rad/s: from one sweep to the next the roll rate changes
  // by up to 0.19 rad/s, so the twist of the motion registered before bends each scan (at 30 m
  // up to 0.5 m at the sweep's end). sweep_motion estimates the twist's change with the pose.
  constexpr double kRollRate = 0.3;
  std::vector<PointCloud> scans;
  for (int k = 0; k < 25; ++k) scans.push_back(moving_scan(k, true, kRollRate));
  const Errors two = track(scans, true, 2, TimeSource::kField, false, kRollRate);
  const Errors estimated = track(scans, true, 2, TimeSource::kField, true, kRollRate);
  std::printf(
      "pose error at the stamp over 25 rolling sweeps: 2 passes mean %.4f max %.3f m "
      "%.3f deg; with the sweep's motion estimated mean %.4f max %.3f m %.3f deg\n",
      two.mean_m, two.max_m, two.max_deg, estimated.mean_m, estimated.max_m, estimated.max_deg);
  // Measured: 2 passes mean 0.113 m, max 0.262 m / 1.106 deg; estimated 0.068, 0.115 / 0.460.
  EXPECT_LT(estimated.max_m, 0.15);
  EXPECT_LT(estimated.max_deg, 0.6 * two.max_deg);
  EXPECT_LT(estimated.mean_m, 0.75 * two.mean_m);
}

TEST(DeskewTrackerWobble, TheSweepsMotionIsEstimatedOnlyAtTheMinimumSpeed) {
  // The drive runs at 25 m/s: a minimum of 20 m/s estimates as without one, 30 m/s never does.
  constexpr double kRollRate = 0.3;
  std::vector<PointCloud> scans;
  for (int k = 0; k < 8; ++k) scans.push_back(moving_scan(k, true, kRollRate));
  const Errors off = track(scans, true, 2, TimeSource::kField, false, kRollRate);
  const Errors any_speed = track(scans, true, 2, TimeSource::kField, true, kRollRate, 0.0);
  const Errors below = track(scans, true, 2, TimeSource::kField, true, kRollRate, 20.0);
  const Errors above = track(scans, true, 2, TimeSource::kField, true, kRollRate, 30.0);
  bool estimated_differs = false;
  for (std::size_t k = 0; k < scans.size(); ++k) {
    EXPECT_TRUE(below.poses[k].matrix() == any_speed.poses[k].matrix()) << k;
    EXPECT_TRUE(above.poses[k].matrix() == off.poses[k].matrix()) << k;
    estimated_differs =
        estimated_differs || !(any_speed.poses[k].matrix() == off.poses[k].matrix());
  }
  EXPECT_TRUE(estimated_differs);
}

TEST_F(DeskewTracker, SelfHitsAreDroppedInTheFrameOfTheirFiring) {
  // A mirror-sized body on the sensor's left, fixed to the sensor: its points are hit a quarter
  // or three quarters into the clockwise sweep, when the sensor has moved 0.6 or 1.9 m at
  // 25 m/s. Deskew would move them that far along x, out of the 1 m box that drops them.
  const Eigen::Vector3d box_min(-0.5, 0.8, -0.3), box_max(0.5, 1.2, 0.0);
  PointCloud body;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.02f, 0.98f);
  for (int i = 0; i < 400; ++i)
    body.points.emplace_back(-0.5f + 1.0f * u(rng), 0.8f + 0.4f * u(rng), -0.3f + 0.3f * u(rng));
  std::vector<float> body_times;
  times_from_azimuth(body, AzimuthTiming{}, body_times);
  TrackerConfig config;
  config.deskew.enabled = true;
  config.filter.ego = EgoFilterMode::kBox;
  config.filter.ego_box_min = box_min;
  config.filter.ego_box_max = box_max;
  Tracker tracker(config);
  for (int k = 0; k < 6; ++k) {
    PointCloud scan = scans_with_times()[static_cast<std::size_t>(k)];
    int world_in_box = 0;
    for (const Eigen::Vector3f& p : scan.points) world_in_box += inside_box(p, box_min, box_max);
    scan.points.insert(scan.points.end(), body.points.begin(), body.points.end());
    scan.times.insert(scan.times.end(), body_times.begin(), body_times.end());
    const FrameResult r =
        tracker.process(scan, SweepTiming{Stamp::from_seconds(k * Drive::kPeriod)});
    ASSERT_TRUE(r.deskewed);
    EXPECT_EQ(r.self_hits, 400 + world_in_box) << "scan " << k;
  }
}

TEST_F(DeskewTracker, TimesFromTheAzimuthWhenTheScanHasNone) {
  const Errors field = track(scans_with_times(), true, 2);
  const Errors azimuth = track(scans_without_times(), true, 2, TimeSource::kFieldOrAzimuth);
  // The scans' times are their azimuth's, to 1 ms.
  EXPECT_LT(azimuth.max_m, 0.15);
  EXPECT_NEAR(azimuth.mean_m, field.mean_m, 0.05);
}

TEST_F(DeskewTracker, WithoutDeskewTheTimedEntryIsBitIdentical) {
  TrackerConfig config;
  Tracker plain(config), timed(config);
  for (std::size_t k = 0; k < 6; ++k) {
    const FrameResult a = plain.process(scans_with_times()[k]);
    // Equal intervals (to the stamps' nanoseconds): the prediction is the last motion as is.
    const FrameResult b = timed.process(
        scans_with_times()[k], SweepTiming{Stamp::from_seconds(0.1 * static_cast<double>(k))});
    EXPECT_EQ(0, std::memcmp(a.pose.matrix().data(), b.pose.matrix().data(), 16 * sizeof(double)));
    EXPECT_FALSE(b.deskewed);
  }
  // A deskewing tracker whose scans have no time field registers them as they are.
  config.deskew.enabled = true;
  Tracker fallback(config);
  Tracker raw(TrackerConfig{});
  for (std::size_t k = 0; k < 6; ++k) {
    const FrameResult a = raw.process(scans_without_times()[k]);
    const FrameResult b =
        fallback.process(scans_without_times()[k], SweepTiming{Stamp::from_seconds(0.1 * k)});
    EXPECT_FALSE(b.deskewed);
    EXPECT_EQ(0, std::memcmp(a.pose.matrix().data(), b.pose.matrix().data(), 16 * sizeof(double)));
  }
}

TEST_F(DeskewTracker, StampsMustIncreaseWithoutDeskewToo) {
  Tracker tracker{TrackerConfig{}};
  tracker.process(scans_without_times()[0], SweepTiming{Stamp::from_seconds(1.0)});
  EXPECT_THROW(tracker.process(scans_without_times()[1], SweepTiming{Stamp::from_seconds(0.9)}),
               std::invalid_argument);
  EXPECT_EQ(tracker.frames(), 1u);
}

TEST_F(DeskewTracker, StampsMustIncreaseAndTimesBeValid) {
  TrackerConfig config;
  config.deskew.enabled = true;
  Tracker tracker(config);
  tracker.process(scans_with_times()[0], SweepTiming{Stamp::from_seconds(1.0)});
  EXPECT_THROW(tracker.process(scans_with_times()[1], SweepTiming{Stamp::from_seconds(1.0)}),
               std::invalid_argument);
  PointCloud bad = scans_with_times()[1];
  bad.times[3] = 2.0f;
  EXPECT_THROW(tracker.process(bad, SweepTiming{Stamp::from_seconds(1.1)}), std::invalid_argument);
  EXPECT_EQ(tracker.frames(), 1u);  // nothing changed
  EXPECT_NO_THROW(tracker.process(scans_with_times()[1], SweepTiming{Stamp::from_seconds(1.1)}));
}

TEST_F(DeskewTracker, SkippedFrameKeepsTheMotion) {
  // Frame 4 cannot be read: its pose is extrapolated and frame 5 is registered from there.
  TrackerConfig config;
  config.deskew.enabled = true;
  Tracker tracker(config);
  const Eigen::Isometry3d origin = Drive::pose(0.0).inverse();
  std::vector<Eigen::Isometry3d> poses;
  for (std::size_t k = 0; k < 12; ++k) {
    const SweepTiming timing{Stamp::from_seconds(k * Drive::kPeriod)};
    if (k == 4) {
      const Eigen::Isometry3d before = poses.back() * (poses[2].inverse() * poses[3]);
      const FrameResult skipped = tracker.skip_frame(timing);
      EXPECT_FALSE(skipped.registered);
      EXPECT_FALSE(skipped.keyframe);
      EXPECT_LT((skipped.pose.matrix() - before.matrix()).cwiseAbs().maxCoeff(), 1e-9);
      poses.push_back(skipped.pose);
      continue;
    }
    const FrameResult r = tracker.process(scans_with_times()[k], timing);
    poses.push_back(r.pose);
    if (k > 4) {
      const Eigen::Isometry3d error = (origin * Drive::pose(k * Drive::kPeriod)).inverse() * r.pose;
      EXPECT_TRUE(r.registered) << k;
      EXPECT_LT(error.translation().norm(), 0.15) << k;
    }
  }
  EXPECT_EQ(tracker.frames(), 12u);
}

}  // namespace
}  // namespace litamin2

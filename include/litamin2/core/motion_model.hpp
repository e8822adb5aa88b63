#pragma once
/// The tracker's constant-velocity motion model (added to LiTAMIN2, which predicts each scan's
/// pose from the last frame's motion): the last motion scaled to the next scan's interval.

#include <Eigen/Geometry>

namespace litamin2 {

/// `motion` scaled by s: s times its translation and s times its rotation angle about the same
/// axis (s = 1 gives `motion` up to rounding).
Eigen::Isometry3d scaled_motion(const Eigen::Isometry3d& motion, double s);

/// The factor by which the last motion, which took `previous_interval` seconds, is scaled to
/// predict the motion over the next `interval` seconds: interval / previous_interval, at most
/// `max_ratio`; 1 when either interval is unknown (<= 0).
double interval_ratio(double interval, double previous_interval, double max_ratio);

}  // namespace litamin2

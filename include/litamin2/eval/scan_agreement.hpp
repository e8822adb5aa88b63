#pragma once
/// How well two consecutive scans agree under an estimated motion, without ground truth: the
/// median distance from the later scan's points, moved into the earlier scan's frame, to their
/// nearest neighbour in the earlier scan. On simulated VLP-16 street scans at their true motion
/// it is 0.15 m (median over frames, steps up to 3.5 m); a motion off by a metre gives about
/// 1 m (docs/accuracy.md, "Breaks in the real VLP-16 drive").

#include "litamin2/core/point_cloud.hpp"

#include <Eigen/Geometry>

namespace litamin2::eval {

struct ScanAgreementConfig {
  /// Points nearer to or farther from the sensor than these are left out, metres (self-hits;
  /// far points seen by one of the scans only).
  double min_range = 3.0;
  double max_range = 30.0;
  /// Points below this height in the sensor frame are left out, metres (the ground: its ring
  /// arcs move with the sensor, so they agree under any horizontal motion).
  double min_z = -1.0;
  /// Every stride-th kept point of the later scan is measured.
  int stride = 4;
};

/// Throws std::invalid_argument unless 0 <= min_range < max_range, both finite, min_z finite
/// and stride >= 1.
void validate(const ScanAgreementConfig& config);

struct ScanAgreement {
  /// Median nearest-neighbour distance, metres; NaN when either scan has no kept point.
  double median_m = 0.0;
  /// Points of the later scan measured.
  int measured = 0;
};

/// `motion` is the earlier scan's sensor pose to the later one's (P_earlier^-1 P_later), so a
/// later point p lies at motion * p in the earlier frame.
ScanAgreement scan_agreement(const PointCloud& earlier, const PointCloud& later,
                             const Eigen::Isometry3d& motion, const ScanAgreementConfig& config);

}  // namespace litamin2::eval

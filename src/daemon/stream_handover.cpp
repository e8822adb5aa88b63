#include "litamin2/daemon/stream_handover.hpp"

namespace litamin2::daemon {

Eigen::Isometry3d handover_origin(const HandoverSeed& seed, Stamp stamp,
                                  double max_extrapolation_s) {
  const double dt = static_cast<double>(stamp.nanoseconds - seed.stamp.nanoseconds) * 1e-9;
  if (!seed.twist || !(dt > 0.0) || dt > max_extrapolation_s) return seed.pose;
  return seed.pose * motion_after(*seed.twist, dt);
}

}  // namespace litamin2::daemon

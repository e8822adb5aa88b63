#include "litamin2/daemon/stream_handover.hpp"

#include <algorithm>

namespace litamin2::daemon {

Eigen::Isometry3d handover_origin(const HandoverSeed& seed, Stamp stamp,
                                  double max_extrapolation_s) {
  const double dt = static_cast<double>(stamp.nanoseconds - seed.stamp.nanoseconds) * 1e-9;
  if (!seed.twist || !(dt > 0.0) || dt > max_extrapolation_s) return seed.pose;
  return seed.pose * motion_after(*seed.twist, dt);
}

std::vector<Keyframe> select_map_seed(std::vector<Keyframe> candidates, Stamp last_stamp,
                                      const MapSeedLimits& limits) {
  const auto oldest = last_stamp.nanoseconds - static_cast<std::int64_t>(limits.max_age_s * 1e9);
  candidates.erase(std::remove_if(candidates.begin(), candidates.end(),
                                  [&](const Keyframe& k) { return k.stamp.nanoseconds < oldest; }),
                   candidates.end());
  std::sort(candidates.begin(), candidates.end(),
            [](const Keyframe& a, const Keyframe& b) { return a.key.id < b.key.id; });
  candidates.erase(
      std::unique(candidates.begin(), candidates.end(),
                  [](const Keyframe& a, const Keyframe& b) { return a.key.id == b.key.id; }),
      candidates.end());
  if (candidates.size() > limits.keyframes)
    candidates.erase(candidates.begin(),
                     candidates.end() - static_cast<std::ptrdiff_t>(limits.keyframes));
  return candidates;
}

TrackerSeed tracker_seed(const HandoverSeed& seed, Stamp stamp, double max_extrapolation_s,
                         const Eigen::Isometry3d& sensor_in_base) {
  const Eigen::Isometry3d e = sensor_in_base;
  const Eigen::Isometry3d e_inv = sensor_in_base.inverse();
  TrackerSeed out;
  out.predicted = e_inv * handover_origin(seed, stamp, max_extrapolation_s) * e;
  if (seed.twist && seed.interval_s > 0.0) {
    out.velocity = e_inv * motion_after(*seed.twist, seed.interval_s) * e;
    out.interval_s = seed.interval_s;
  }
  out.keyframes.reserve(seed.map_keyframes.size());
  for (const Keyframe& k : seed.map_keyframes) {
    SeedKeyframe s;
    s.pose = e_inv * k.odom_pose;
    s.voxel_size = k.voxel_size;
    s.distributions = k.distributions;
    out.keyframes.push_back(std::move(s));
  }
  return out;
}

}  // namespace litamin2::daemon

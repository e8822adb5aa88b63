#include "litamin2/sim/ground_clearance.hpp"

#include <algorithm>
#include <cmath>

namespace litamin2::sim {

GroundClearance check_ground_clearance(const World& world,
                                       const std::vector<Eigen::Isometry3d>& sensor_poses,
                                       double mount_height, double tolerance_m) {
  GroundClearance out;
  for (std::size_t i = 0; i < sensor_poses.size(); ++i) {
    const Eigen::Vector3d p = sensor_poses[i].translation();
    const double off = std::abs(p.z() - world.ground_height(p.x(), p.y()) - mount_height);
    out.worst_m = std::max(out.worst_m, off);
    if (!(off <= tolerance_m)) {
      if (out.poses_off == 0) out.first_off = i;
      out.last_off = i;
      ++out.poses_off;
    }
  }
  return out;
}

}  // namespace litamin2::sim

#include "litamin2/sim/drivable_height.hpp"

#include <cmath>

namespace litamin2::sim {

std::size_t limit_grade(std::vector<Eigen::Isometry3d>& poses, double max_grade,
                        double step_slack_m) {
  std::size_t changed = 0;
  for (std::size_t i = 1; i < poses.size(); ++i) {
    const Eigen::Vector3d previous = poses[i - 1].translation();
    const Eigen::Vector3d current = poses[i].translation();
    const double run = (current.head<2>() - previous.head<2>()).norm();
    const double limit = max_grade * run + step_slack_m;
    const double rise = current.z() - previous.z();
    if (std::abs(rise) <= limit) continue;
    poses[i].translation().z() = previous.z() + std::copysign(limit, rise);
    ++changed;
  }
  return changed;
}

}  // namespace litamin2::sim

#include "litamin2/sim/trajectory_window.hpp"

#include <algorithm>

namespace litamin2::sim {

std::vector<Eigen::Isometry3d> trajectory_window(const std::vector<Eigen::Isometry3d>& trajectory,
                                                 std::size_t first, std::size_t last,
                                                 double margin) {
  last = std::min(last, trajectory.size());
  if (first >= last) return {};
  std::size_t a = first;
  for (double d = 0; a > 0 && d < margin; --a) {
    d += (trajectory[a].translation() - trajectory[a - 1].translation()).norm();
  }
  std::size_t b = last;  // exclusive
  for (double d = 0; b < trajectory.size() && d < margin; ++b) {
    d += (trajectory[b].translation() - trajectory[b - 1].translation()).norm();
  }
  return {trajectory.begin() + static_cast<std::ptrdiff_t>(a),
          trajectory.begin() + static_cast<std::ptrdiff_t>(b)};
}

}  // namespace litamin2::sim

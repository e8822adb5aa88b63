#include "litamin2/sim/fleet.hpp"

#include <stdexcept>

namespace litamin2::sim {

std::vector<FleetVehicle> plan_fleet(const std::vector<Eigen::Isometry3d>& trajectory,
                                     std::size_t first, std::size_t count,
                                     const FleetOptions& options) {
  if (options.vehicles < 1) throw std::invalid_argument("plan_fleet: vehicles must be >= 1");
  if (count == 0) throw std::invalid_argument("plan_fleet: count must be > 0");
  if (first + count > trajectory.size()) {
    throw std::invalid_argument("plan_fleet: frames exceed the trajectory");
  }
  const std::size_t n = trajectory.size();
  std::vector<FleetVehicle> fleet;
  for (int k = 0; k < options.vehicles; ++k) {
    // Window start: shifted forward if possible, else backward, else as far as it goes.
    const std::size_t shift = static_cast<std::size_t>(k / 2) * count / 4;
    std::size_t start = first;
    if (first + shift + count <= n) {
      start = first + shift;
    } else if (first >= shift) {
      start = first - shift;
    } else {
      start = n - count;
    }
    const bool reverse = k % 2 == 1;
    FleetVehicle v;
    for (std::size_t i = 0; i < count; ++i) {
      const std::size_t src = reverse ? start + count - 1 - i : start + i;
      Eigen::Isometry3d T = trajectory[src];
      if (reverse) {
        T.translation() += T.linear().col(1) * options.lane_offset;
        T.linear() =
            T.linear() * Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      }
      v.sensor_poses.push_back(T);
      v.source_frames.push_back(src);
    }
    v.description = std::string(reverse ? "reverse" : "forward") + " frames " +
                    std::to_string(start) + ".." + std::to_string(start + count - 1) +
                    (reverse ? ", lane offset " + std::to_string(options.lane_offset) + " m" : "");
    fleet.push_back(std::move(v));
  }
  return fleet;
}

}  // namespace litamin2::sim

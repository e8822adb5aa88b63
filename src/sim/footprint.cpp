#include "litamin2/sim/footprint.hpp"

#include "litamin2/sim/grid.hpp"

namespace litamin2::sim {
namespace {

std::int64_t cell_of(const Eigen::Vector2d& q) {
  return cell_key(static_cast<int>(std::floor(q.x())), static_cast<int>(std::floor(q.y())));
}

}  // namespace

bool Occupancy::free(const Footprint& f) const {
  return f.all_points(false, [&](const Eigen::Vector2d& q) { return !cells_.count(cell_of(q)); });
}

void Occupancy::occupy(const Footprint& f) {
  f.all_points(false, [&](const Eigen::Vector2d& q) {
    cells_.insert(cell_of(q));
    return true;
  });
}

}  // namespace litamin2::sim

#pragma once
/// Integer grids over the world plane, as the world builder uses them for its hash maps and sets
/// (path index, tiles, layout occupancy): cell keys and the cells a disc touches.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>

namespace litamin2::sim {

/// Hash key of the grid cell (x, y): x's 32 bits above y's. Shifted as unsigned (a negative
/// signed value shifted left is undefined behaviour in C++17); the keys are the same bits.
inline std::int64_t cell_key(int x, int y) {
  const std::uint64_t high = static_cast<std::uint32_t>(x);
  return static_cast<std::int64_t>((high << 32) ^ static_cast<std::uint32_t>(y));
}

/// Calls visit(x, y) for every cell of a grid of spacing `cell` (cell (x, y) covers
/// [x, x+1) x [y, y+1) times `cell`) that comes within `radius` of `centre`; x outer, y inner,
/// both increasing.
template <class Visit>
void for_each_cell_near(const Eigen::Vector2d& centre, double radius, double cell, Visit&& visit) {
  const int x0 = static_cast<int>(std::floor((centre.x() - radius) / cell));
  const int x1 = static_cast<int>(std::floor((centre.x() + radius) / cell));
  const int y0 = static_cast<int>(std::floor((centre.y() - radius) / cell));
  const int y1 = static_cast<int>(std::floor((centre.y() + radius) / cell));
  for (int x = x0; x <= x1; ++x) {
    for (int y = y0; y <= y1; ++y) {
      const double dx = std::max({x * cell - centre.x(), 0.0, centre.x() - (x + 1) * cell});
      const double dy = std::max({y * cell - centre.y(), 0.0, centre.y() - (y + 1) * cell});
      if (dx * dx + dy * dy <= radius * radius) visit(x, y);
    }
  }
}

}  // namespace litamin2::sim

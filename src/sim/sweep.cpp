#include "litamin2/sim/sweep.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace litamin2::sim {

double SweepOptions::column_azimuth(int column, int steps) const {
  const double turned = 2.0 * M_PI * column / steps;
  if (is_default_layout()) return turned;  // bit-identical to the original layout
  return start_azimuth_deg * M_PI / 180.0 + (clockwise ? -turned : turned);
}

double SweepOptions::column_time(int column, int steps) const {
  return duration * static_cast<double>(column) / static_cast<double>(steps);
}

bool SweepOptions::is_default_layout() const {
  return start_azimuth_deg == 0.0 && !clockwise;
}

void SweepOptions::validate() const {
  if (!(duration > 0.0 && duration <= 1.0)) {
    throw std::invalid_argument("sweep: duration " + std::to_string(duration) +
                                " s must be in (0, 1]");
  }
  if (!std::isfinite(start_azimuth_deg) || std::abs(start_azimuth_deg) > 360.0) {
    throw std::invalid_argument("sweep: start azimuth " + std::to_string(start_azimuth_deg) +
                                " deg must be within [-360, 360]");
  }
}

}  // namespace litamin2::sim

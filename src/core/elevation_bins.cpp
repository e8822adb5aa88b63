#include "litamin2/core/elevation_bins.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace litamin2 {

ElevationBins::ElevationBins(double low_deg, double width_deg, int bins) {
  const double high_deg = low_deg + width_deg * bins;
  if (!(width_deg > 0.0) || bins <= 0 || !(low_deg > -90.0) || !(high_deg < 90.0))
    throw std::invalid_argument("ElevationBins: bins must lie within (-90, 90) deg");
  constexpr double kRadPerDeg = M_PI / 180.0;
  edges_.resize(static_cast<std::size_t>(bins) + 1);
  for (int k = 0; k <= bins; ++k) edges_[k] = std::tan((low_deg + k * width_deg) * kRadPerDeg);
  double narrowest = edges_[1] - edges_[0];
  for (int k = 1; k < bins; ++k) narrowest = std::min(narrowest, edges_[k + 1] - edges_[k]);
  // Cells of half the narrowest bin: a cell holds at most one edge, with margin for rounding.
  cells_per_unit_ = 2.0 / narrowest;
  const auto cells =
      static_cast<std::size_t>(std::ceil((edges_.back() - edges_.front()) * cells_per_unit_));
  first_bin_.resize(std::max<std::size_t>(cells, 1));
  int b = 0;
  for (std::size_t c = 0; c < first_bin_.size(); ++c) {
    const double lower = edges_.front() + static_cast<double>(c) / cells_per_unit_;
    while (b + 1 < bins && edges_[b + 1] <= lower) ++b;
    first_bin_[c] = b;
  }
}

}  // namespace litamin2

#pragma once
/// Equal-width bins of a direction's elevation angle, found without atan2.

#include <cstddef>
#include <vector>

namespace litamin2 {

/// Bins `width_deg` wide from `low_deg` of the elevation atan2(z, horizontal) of directions with
/// horizontal > 0, inside (-90, 90) deg. tan is increasing there, so a direction is in bin k
/// exactly when tan(edge k) <= z / horizontal < tan(edge k + 1): a uniform table over
/// z / horizontal, with cells narrower than the narrowest bin, gives the bin of a cell's lower
/// end, and a comparison with the neighbouring edges settles the rest. Per point that is one
/// division instead of an atan2 (the sensor recognition bins every point of a stream's first
/// scan). A direction within rounding of an edge may fall on either side of it.
class ElevationBins {
 public:
  /// Throws std::invalid_argument unless width_deg > 0, bins > 0 and the bins lie within
  /// (-90, 90) deg.
  ElevationBins(double low_deg, double width_deg, int bins);

  int size() const { return static_cast<int>(edges_.size()) - 1; }

  /// The bin of direction (horizontal, z); -1 outside every bin or unless horizontal > 0.
  int bin(double z, double horizontal) const {
    if (!(horizontal > 0.0)) return -1;
    const double t = z / horizontal;
    if (!(t >= edges_.front() && t < edges_.back())) return -1;
    auto cell = static_cast<std::size_t>((t - edges_.front()) * cells_per_unit_);
    if (cell >= first_bin_.size()) cell = first_bin_.size() - 1;
    int b = first_bin_[cell];
    if (t >= edges_[b + 1])
      ++b;
    else if (t < edges_[b])
      --b;
    return b;
  }

 private:
  std::vector<double> edges_;    ///< tan of the bins' edges, size() + 1, increasing
  std::vector<int> first_bin_;   ///< per table cell: the bin holding the cell's lower end
  double cells_per_unit_ = 0.0;  ///< table cells per unit of z / horizontal
};

}  // namespace litamin2

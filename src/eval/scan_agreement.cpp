#include "litamin2/eval/scan_agreement.hpp"

#include <nanoflann.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace litamin2::eval {
namespace {

struct Cloud {
  std::vector<Eigen::Vector3d> points;
  std::size_t kdtree_get_point_count() const { return points.size(); }
  double kdtree_get_pt(std::size_t i, std::size_t d) const { return points[i](d); }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};
using Tree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Cloud>, Cloud, 3>;

bool kept(const Eigen::Vector3f& p, const ScanAgreementConfig& c) {
  const double r = p.cast<double>().norm();
  return std::isfinite(r) && r >= c.min_range && r <= c.max_range && p.z() >= c.min_z;
}

}  // namespace

void validate(const ScanAgreementConfig& c) {
  if (!(std::isfinite(c.min_range) && std::isfinite(c.max_range) && c.min_range >= 0.0 &&
        c.min_range < c.max_range))
    throw std::invalid_argument("scan agreement: need 0 <= min_range < max_range, both finite");
  if (!std::isfinite(c.min_z)) throw std::invalid_argument("scan agreement: min_z not finite");
  if (c.stride < 1) throw std::invalid_argument("scan agreement: stride must be at least 1");
}

ScanAgreement scan_agreement(const PointCloud& earlier, const PointCloud& later,
                             const Eigen::Isometry3d& motion, const ScanAgreementConfig& config) {
  validate(config);
  Cloud target;
  for (const Eigen::Vector3f& p : earlier.points)
    if (kept(p, config)) target.points.push_back(p.cast<double>());
  std::vector<double> distances;
  if (!target.points.empty()) {
    Tree tree(3, target);
    tree.buildIndex();
    int seen = 0;
    for (const Eigen::Vector3f& p : later.points) {
      if (!kept(p, config) || (seen++ % config.stride) != 0) continue;
      const Eigen::Vector3d q = motion * p.cast<double>();
      std::size_t index = 0;
      double squared = 0.0;
      nanoflann::KNNResultSet<double> result(1);
      result.init(&index, &squared);
      tree.findNeighbors(result, q.data(), nanoflann::SearchParams());
      distances.push_back(std::sqrt(squared));
    }
  }
  ScanAgreement out;
  out.measured = static_cast<int>(distances.size());
  if (distances.empty()) {
    out.median_m = std::numeric_limits<double>::quiet_NaN();
    return out;
  }
  const auto middle = distances.begin() + distances.size() / 2;
  std::nth_element(distances.begin(), middle, distances.end());
  out.median_m = *middle;
  return out;
}

}  // namespace litamin2::eval

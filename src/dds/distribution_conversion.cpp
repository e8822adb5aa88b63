#include "litamin2/dds/distribution_conversion.hpp"

#include "litamin2/core/value_checks.hpp"

#include <Eigen/LU>
#include <limits>

namespace litamin2::dds {

litamin2::msg::VoxelDistribution to_voxel_distribution(const Distribution& d) {
  litamin2::msg::VoxelDistribution v;
  v.mean({static_cast<float>(d.mean.x()), static_cast<float>(d.mean.y()),
          static_cast<float>(d.mean.z())});
  v.cov({static_cast<float>(d.cov(0, 0)), static_cast<float>(d.cov(0, 1)),
         static_cast<float>(d.cov(0, 2)), static_cast<float>(d.cov(1, 1)),
         static_cast<float>(d.cov(1, 2)), static_cast<float>(d.cov(2, 2))});
  v.count(static_cast<std::uint32_t>(d.count < 0 ? 0 : d.count));
  return v;
}

std::optional<std::string> convert_distribution(const litamin2::msg::VoxelDistribution& v,
                                                Distribution& d) {
  const auto& m = v.mean();
  d.mean = Eigen::Vector3d(m[0], m[1], m[2]);
  if (auto why = checks::position_error(d.mean)) return "mean " + *why;
  const auto& c = v.cov();
  d.cov << c[0], c[1], c[2], c[1], c[3], c[4], c[2], c[4], c[5];
  if (auto why = checks::covariance_error<3>(d.cov)) return "covariance " + *why;
  if (v.count() == 0) return std::string("point count is 0");
  if (v.count() > static_cast<std::uint32_t>(std::numeric_limits<int>::max()))
    return "point count " + std::to_string(v.count()) + " is beyond 2^31 - 1";
  d.count = static_cast<int>(v.count());
  d.shape_cov = d.cov;
  bool invertible = false;
  Eigen::Matrix3d inverse;
  d.cov.computeInverseWithCheck(inverse, invertible);
  d.shape_cov_inv = invertible ? inverse : Eigen::Matrix3d::Identity();
  return std::nullopt;
}

}  // namespace litamin2::dds

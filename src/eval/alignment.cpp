#include "litamin2/eval/alignment.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <stdexcept>

namespace litamin2::eval {

Eigen::Isometry3d Similarity3::rigid() const {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = rotation;
  t.translation() = translation;
  return t;
}

Similarity3 umeyama_alignment(const std::vector<Eigen::Vector3d>& src,
                              const std::vector<Eigen::Vector3d>& dst, bool with_scale) {
  if (src.size() != dst.size()) {
    throw std::invalid_argument("umeyama_alignment: point sets differ in size");
  }
  if (src.empty()) throw std::invalid_argument("umeyama_alignment: empty point sets");

  // Eigen's implementation of Umeyama (1991): centroids, SVD of the cross-covariance, the
  // reflection fix, and the scale from the singular values over the source variance.
  Eigen::Matrix3Xd from(3, static_cast<Eigen::Index>(src.size()));
  Eigen::Matrix3Xd to(3, static_cast<Eigen::Index>(dst.size()));
  for (std::size_t i = 0; i < src.size(); ++i) {
    from.col(static_cast<Eigen::Index>(i)) = src[i];
    to.col(static_cast<Eigen::Index>(i)) = dst[i];
  }
  const Eigen::Matrix4d transform = Eigen::umeyama(from, to, with_scale);

  Similarity3 result;
  result.scale = with_scale ? transform.block<3, 1>(0, 0).norm() : 1.0;
  // A single point (no spread) has no scale to fit: Eigen then divides by a zero variance.
  if (!std::isfinite(result.scale) || result.scale <= 0.0) {
    result.scale = 1.0;
    result.rotation.setIdentity();
    result.translation = to.rowwise().mean() - from.rowwise().mean();
    return result;
  }
  result.rotation = transform.block<3, 3>(0, 0) / result.scale;
  result.translation = transform.block<3, 1>(0, 3);
  return result;
}

}  // namespace litamin2::eval

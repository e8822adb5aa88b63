#pragma once
/// Closed-form least-squares alignment of two point sets (Umeyama 1991, Horn without scale).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace litamin2::eval {

/// Similarity transform x -> scale * rotation * x + translation.
struct Similarity3 {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  double scale = 1.0;

  /// Applies the transform to a point.
  Eigen::Vector3d operator()(const Eigen::Vector3d& x) const {
    return scale * (rotation * x) + translation;
  }
  /// The rigid part (rotation, translation) as an isometry; scale is not included.
  Eigen::Isometry3d rigid() const;
};

/// Transform T minimising sum_i |dst[i] - T(src[i])|^2, in closed form via the SVD of the
/// cross-covariance (Umeyama). With with_scale == false the scale is fixed to 1 (SE(3), Horn).
/// The rotation is always proper (det = +1). Throws std::invalid_argument if the sizes differ or
/// the sets are empty. Degenerate sets (one point, collinear points) give one of the optimal
/// solutions.
Similarity3 umeyama_alignment(const std::vector<Eigen::Vector3d>& src,
                              const std::vector<Eigen::Vector3d>& dst, bool with_scale = false);

}  // namespace litamin2::eval

#include "litamin2/mapping/odometry_covariance.hpp"

#include "litamin2/core/so3.hpp"

namespace litamin2::mapping {

Matrix6d relative_pose_covariance(const Eigen::Isometry3d& pose_a, const Eigen::Isometry3d& pose_b,
                                  const Matrix6d& left_covariance_b) {
  const Eigen::Matrix3d ra_t = pose_a.linear().transpose();
  Matrix6d j = Matrix6d::Zero();
  j.topLeftCorner<3, 3>() = -ra_t * skew(pose_b.translation());
  j.topRightCorner<3, 3>() = ra_t;
  j.bottomLeftCorner<3, 3>() = pose_b.linear().transpose();
  const Matrix6d c = j * left_covariance_b * j.transpose();
  return 0.5 * (c + c.transpose());
}

}  // namespace litamin2::mapping

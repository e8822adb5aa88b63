#include "litamin2/eval/relative_error.hpp"

#include "litamin2/eval/rotation_angle.hpp"

namespace litamin2::eval {

Eigen::Isometry3d relative_motion(const Eigen::Isometry3d& from, const Eigen::Isometry3d& to) {
  const Eigen::Matrix3d from_rotation_t = from.linear().transpose();
  Eigen::Isometry3d delta = Eigen::Isometry3d::Identity();
  delta.linear() = from_rotation_t * to.linear();
  delta.translation() = from_rotation_t * (to.translation() - from.translation());
  return delta;
}

RelativeError relative_error(const Eigen::Isometry3d& gt_first, const Eigen::Isometry3d& gt_last,
                             const Eigen::Isometry3d& est_first,
                             const Eigen::Isometry3d& est_last) {
  const Eigen::Isometry3d delta_gt = relative_motion(gt_first, gt_last);
  const Eigen::Isometry3d delta_est = relative_motion(est_first, est_last);
  // error = inv(delta_est) * delta_gt.
  const Eigen::Vector3d error_translation =
      delta_est.linear().transpose() * (delta_gt.translation() - delta_est.translation());
  RelativeError error;
  error.translation = error_translation.norm();
  error.rotation = rotation_angle_between(delta_est.linear(), delta_gt.linear());
  return error;
}

}  // namespace litamin2::eval

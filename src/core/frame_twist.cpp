#include "litamin2/core/frame_twist.hpp"

namespace litamin2 {

TwistEstimate twist_between(const Eigen::Isometry3d& previous, const Eigen::Isometry3d& pose,
                            const Matrix6d& left_covariance, double seconds) {
  TwistEstimate out;
  // twist_from_motion checks `seconds`.
  out.twist = twist_from_motion(previous.inverse() * pose, seconds);
  // The motion's logarithm xi = (w, v) = seconds * twist, and ad_xi = [[w]x, 0; [v]x, [w]x].
  const Eigen::Vector3d w = seconds * out.twist.angular;
  const Eigen::Vector3d v = seconds * out.twist.linear;
  Matrix6d ad = Matrix6d::Zero();
  ad.topLeftCorner<3, 3>() = skew(w);
  ad.bottomLeftCorner<3, 3>() = skew(v);
  ad.bottomRightCorner<3, 3>() = skew(w);
  // J_r^-1(xi) to second order (see the header).
  const Matrix6d jr_inv = Matrix6d::Identity() + 0.5 * ad + (1.0 / 12.0) * ad * ad;
  // J Ad_{T^-1} C Ad_{T^-1}^T J^T / dt^2.
  const Matrix6d body = transform_left_covariance(left_covariance, pose.inverse());
  out.covariance = jr_inv * body * jr_inv.transpose() / (seconds * seconds);
  out.covariance = 0.5 * (out.covariance + out.covariance.transpose()).eval();
  return out;
}

}  // namespace litamin2

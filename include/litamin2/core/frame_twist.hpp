#pragma once
/// The body velocity between two consecutive poses of a stream, with its covariance: what
/// nav_msgs/Odometry's twist carries (in the child frame, as ROS defines it).
///
/// Velocity: xi = Log(P^-1 T) / dt (twist_from_motion, SE(3)'s logarithm), P the previous pose,
/// T the current one, dt the time between their stamps: the constant body twist that moves P
/// to T, expressed in the child (body) frame.
///
/// Covariance: the current pose's covariance C is of the left update (phi, tau) in the odometry
/// frame (Tracker's FrameResult::covariance). A left perturbation of T is a right perturbation
/// of the motion, P^-1 exp(d) T = (P^-1 T) exp(Ad_{T^-1} d), so the motion's body-frame
/// perturbation e has covariance Ad_{T^-1} C Ad_{T^-1}^T. To first order in e the logarithm
/// moves by Log(M exp(e)) = Log(M) + J_r^-1(xi) e, xi = Log(M) = (w, v), with SE(3)'s inverse
/// right Jacobian J_r^-1(xi) = I + ad_xi / 2 + ad_xi^2 / 12 + O(|xi|^3), ad_xi = [[w]x, 0;
/// [v]x, [w]x] (the series, cut after the second-order term: below 0.1 % for the 0.1 rad and
/// 1 m a frame of a 10 Hz sensor; the [v]x / 2 term alone, the angular error's lever arm over
/// half the motion, is 5 % of the lateral velocity's variance at 8 m/s and 0.4 rad/s). So
/// cov(xi) = J_r^-1 Ad_{T^-1} C Ad_{T^-1}^T J_r^-T and, dividing by dt, the twist's is that over
/// dt^2. The previous pose is taken as exact: the scan was registered to the map the previous
/// frames built, so the Hessian covariance C is already relative to them and adding P's own
/// uncertainty would count the shared part twice.

#include "litamin2/core/deskew.hpp"
#include "litamin2/core/so3.hpp"

#include <Eigen/Geometry>

namespace litamin2 {

struct TwistEstimate {
  /// Body twist (angular rad/s, linear m/s) in the current pose's frame.
  Twist twist;
  /// Covariance over (angular, linear), the order of Twist and of the left update.
  Matrix6d covariance = Matrix6d::Zero();
};

/// The twist from `previous` to `pose` over `seconds` (> 0, finite; std::invalid_argument
/// otherwise), with the covariance derived above from `left_covariance`, the covariance of
/// `pose` in (phi, tau) left-update coordinates.
TwistEstimate twist_between(const Eigen::Isometry3d& previous, const Eigen::Isometry3d& pose,
                            const Matrix6d& left_covariance, double seconds);

}  // namespace litamin2

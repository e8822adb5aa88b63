#pragma once
/// Covariance of an odometry edge of the pose graph from the tracker's covariances.
///
/// The tracker gives each keyframe b a covariance C_b of its pose T_b in (phi, tau) coordinates
/// of the left update T <- (exp([phi]x), tau) * T (FrameResult::covariance: 2 sigma^2 H^-1 of
/// the scan-to-map registration, as for ICP's covariance in Censi, "An accurate closed-form
/// estimate of ICP's covariance", ICRA 2007, and Bengtsson & Baerveldt 2003). The map b is
/// registered to is only updated at keyframes, so it is the map built up to the previous
/// keyframe a, which holds a's scan at a's estimated pose: C_b is the uncertainty of b *given*
/// the map, i.e. given a. Hence the covariance of the relative pose T_ab = T_a^-1 T_b is C_b
/// carried to T_ab's coordinates alone; adding C_a as well (as if the two absolute poses were
/// independent measurements) would count a's uncertainty, already in the edge before it, twice.
///
/// Carrying C_b over. Perturb b by the left update: R_b' = exp([phi]x) R_b, t_b' = exp([phi]x)
/// t_b + tau. Then T_ab' = T_a^-1 T_b' has, to first order,
///   R_ab' = R_a^T exp([phi]x) R_b = R_ab exp([R_b^T phi]x)  -> dtheta = R_b^T phi
///   t_ab' = R_a^T (t_b + phi x t_b + tau - t_a)            -> dt = R_a^T (tau - [t_b]x phi)
/// where (dt, dtheta) are the coordinates of the pose graph's residual (pose_graph.cpp:
/// translation difference in a's frame, rotation error on the right of the measurement). With
/// J = [[-R_a^T [t_b]x, R_a^T], [R_b^T, 0]] the edge covariance is J C_b J^T, translation first.

#include "litamin2/core/keyframe.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace litamin2::mapping {

/// J C_b J^T above: the covariance of T_a^-1 T_b in the pose graph's (dt, dtheta) residual
/// coordinates, from b's left-update covariance `left_covariance_b` (rotation block first).
Matrix6d relative_pose_covariance(const Eigen::Isometry3d& pose_a, const Eigen::Isometry3d& pose_b,
                                  const Matrix6d& left_covariance_b);

}  // namespace litamin2::mapping

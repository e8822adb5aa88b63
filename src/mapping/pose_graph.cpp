#include "litamin2/mapping/pose_graph.hpp"

#include <ceres/ceres.h>
#include <Eigen/Cholesky>

#include <algorithm>
#include <memory>
#include <stdexcept>

namespace litamin2::mapping {
namespace {

/// Residual of one relative-pose measurement T_ab between poses (q_a, t_a) and (q_b, t_b), as
/// in Ceres' pose_graph_3d example: the translation error in a's frame and twice the vector
/// part of the rotation error quaternion, whitened: multiplied by the square root of the
/// information, L^-1 for the covariance L L^T (diag(1 / sigma) for independent components), so
/// that its squared norm is the Mahalanobis distance r^T C^-1 r.
struct RelativePoseError {
  RelativePoseError(const Eigen::Isometry3d& measured, const Matrix6d& sqrt_information,
                    const Eigen::Isometry3d& offset_a, const Eigen::Isometry3d& offset_b)
      : q_ab(measured.rotation()),
        t_ab(measured.translation()),
        sqrt_info(sqrt_information),
        q_oa(offset_a.rotation()),
        t_oa(offset_a.translation()),
        q_ob(offset_b.rotation()),
        t_ob(offset_b.translation()) {}

  template <class T>
  bool operator()(const T* qa_ptr, const T* ta_ptr, const T* qb_ptr, const T* tb_ptr,
                  T* residual_ptr) const {
    Eigen::Map<const Eigen::Quaternion<T>> qna(qa_ptr), qnb(qb_ptr);
    Eigen::Map<const Eigen::Matrix<T, 3, 1>> tna(ta_ptr), tnb(tb_ptr);
    // The measured keyframes' poses: node * offset (the offsets are identity between keyframes).
    const Eigen::Quaternion<T> qa = qna * q_oa.template cast<T>();
    const Eigen::Quaternion<T> qb = qnb * q_ob.template cast<T>();
    const Eigen::Matrix<T, 3, 1> ta = qna * t_oa.template cast<T>() + tna;
    const Eigen::Matrix<T, 3, 1> tb = qnb * t_ob.template cast<T>() + tnb;
    const Eigen::Quaternion<T> qa_inv = qa.conjugate();
    const Eigen::Quaternion<T> q_ab_est = qa_inv * qb;
    const Eigen::Matrix<T, 3, 1> t_ab_est = qa_inv * (tb - ta);
    const Eigen::Quaternion<T> dq = q_ab.template cast<T>().conjugate() * q_ab_est;
    Eigen::Matrix<T, 6, 1> r;
    r.template head<3>() = t_ab_est - t_ab.template cast<T>();
    r.template tail<3>() = T(2.0) * dq.vec();
    Eigen::Map<Eigen::Matrix<T, 6, 1>> out(residual_ptr);
    out = sqrt_info.template cast<T>() * r;
    return true;
  }

  Eigen::Quaterniond q_ab;
  Eigen::Vector3d t_ab;
  Matrix6d sqrt_info;
  Eigen::Quaterniond q_oa;
  Eigen::Vector3d t_oa;
  Eigen::Quaterniond q_ob;
  Eigen::Vector3d t_ob;
};

/// L^-1 of the edge's covariance L L^T (Cholesky), or diag(1 / sigma).
Matrix6d sqrt_information(const PoseGraphEdge& e) {
  if (!e.covariance) return e.sigma.cwiseInverse().asDiagonal();
  const Eigen::LLT<Matrix6d> llt(*e.covariance);
  if (llt.info() != Eigen::Success)
    throw std::invalid_argument("pose graph: an edge's covariance is not positive definite");
  return llt.matrixL().solve(Matrix6d::Identity());
}

/// A ground vehicle's sensor stays roughly level: the up axis of the frame the poses are in,
/// seen from the node, is near the node's own up axis. Residual: the horizontal components of
/// R^T e_z, divided by the prior's standard deviation (radians, small-angle).
struct LevelPrior {
  explicit LevelPrior(double sigma) : inv_sigma(1.0 / sigma) {}

  template <class T>
  bool operator()(const T* q_ptr, T* residual) const {
    Eigen::Map<const Eigen::Quaternion<T>> q(q_ptr);
    const Eigen::Matrix<T, 3, 1> up = q.conjugate() * Eigen::Matrix<T, 3, 1>(T(0), T(0), T(1));
    residual[0] = up.x() * T(inv_sigma);
    residual[1] = up.y() * T(inv_sigma);
    return true;
  }

  double inv_sigma;
};

}  // namespace

PoseGraphResult optimize_pose_graph(std::vector<Eigen::Isometry3d>& poses,
                                    const std::vector<bool>& fixed,
                                    const std::vector<PoseGraphEdge>& edges,
                                    const PoseGraphConfig& config) {
  const std::size_t n = poses.size();
  std::vector<Eigen::Quaterniond> q(n);
  std::vector<Eigen::Vector3d> t(n);
  for (std::size_t i = 0; i < n; ++i) {
    q[i] = Eigen::Quaterniond(poses[i].rotation()).normalized();
    t[i] = poses[i].translation();
  }

  // One allocation per edge, not three: the functors live in one array, each cost function
  // holds its functor without owning it, and the cost functions live in another array that the
  // problem does not own either. Every level prior shares one cost function and every robust
  // edge one loss (same sigma, same scale; Ceres allows a cost or loss function in several
  // residual blocks). The residual blocks, their order and their values are those of one cost
  // and loss function per block: the solve is the same, bit for bit.
  using EdgeCost = ceres::AutoDiffCostFunction<RelativePoseError, 6, 4, 3, 4, 3>;
  using LevelCost = ceres::AutoDiffCostFunction<LevelPrior, 2, 4>;
  std::vector<RelativePoseError> edge_functors;
  edge_functors.reserve(edges.size());
  std::vector<EdgeCost> edge_costs;
  edge_costs.reserve(edges.size());
  const double level_sigma = config.level_prior_sigma_deg * M_PI / 180.0;
  LevelPrior level_functor(level_sigma > 0.0 ? level_sigma : 1.0);
  LevelCost level_cost(&level_functor, ceres::DO_NOT_TAKE_OWNERSHIP);
  ceres::CauchyLoss loop_loss(config.loop_loss_scale);
  ceres::EigenQuaternionManifold quaternion_manifold;

  ceres::Problem::Options problem_options;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  for (const PoseGraphEdge& e : edges) {
    edge_functors.emplace_back(e.relative, sqrt_information(e), e.from_offset, e.to_offset);
    edge_costs.emplace_back(&edge_functors.back(), ceres::DO_NOT_TAKE_OWNERSHIP);
    problem.AddResidualBlock(&edge_costs.back(), e.robust ? &loop_loss : nullptr,
                             q[e.from].coeffs().data(), t[e.from].data(), q[e.to].coeffs().data(),
                             t[e.to].data());
  }
  for (std::size_t i = 0; level_sigma > 0.0 && i < n; ++i) {
    if (fixed[i] || !problem.HasParameterBlock(q[i].coeffs().data())) continue;
    problem.AddResidualBlock(&level_cost, nullptr, q[i].coeffs().data());
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!problem.HasParameterBlock(q[i].coeffs().data())) continue;
    problem.SetManifold(q[i].coeffs().data(), &quaternion_manifold);
    if (fixed[i]) {
      problem.SetParameterBlockConstant(q[i].coeffs().data());
      problem.SetParameterBlockConstant(t[i].data());
    }
  }

  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  const auto free_poses = static_cast<int>(std::count(fixed.begin(), fixed.end(), false));
  const bool iterative =
      config.iterative_min_free_poses > 0 && free_poses >= config.iterative_min_free_poses;
  if (iterative) {
    options.linear_solver_type = ceres::CGNR;
    options.preconditioner_type = ceres::JACOBI;
  }
  options.max_num_iterations = config.max_iterations;
  options.num_threads = config.threads;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);

  PoseGraphResult result;
  result.iterative = iterative;
  result.iterations = static_cast<int>(summary.iterations.size());
  result.initial_cost = summary.initial_cost;
  result.final_cost = summary.final_cost;
  result.usable = summary.IsSolutionUsable();
  if (!result.usable) return result;
  std::vector<Eigen::Isometry3d> solved(n, Eigen::Isometry3d::Identity());
  for (std::size_t i = 0; i < n; ++i) {
    solved[i].linear() = q[i].normalized().toRotationMatrix();
    solved[i].translation() = t[i];
  }
  if (!within_reach(poses, solved, edges)) {
    result.usable = false;
    result.diverged = true;
    return result;
  }
  poses = std::move(solved);
  return result;
}

bool within_reach(const std::vector<Eigen::Isometry3d>& before,
                  const std::vector<Eigen::Isometry3d>& after,
                  const std::vector<PoseGraphEdge>& edges) {
  if (before.size() != after.size()) return false;
  double reach = 0.0;
  for (const PoseGraphEdge& e : edges) {
    reach += e.relative.translation().norm() + e.from_offset.translation().norm() +
             e.to_offset.translation().norm();
  }
  for (std::size_t i = 0; i < after.size(); ++i) {
    if (!after[i].matrix().allFinite()) return false;
    if ((after[i].translation() - before[i].translation()).norm() > reach) return false;
  }
  return true;
}

}  // namespace litamin2::mapping

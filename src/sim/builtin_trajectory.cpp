#include "litamin2/sim/builtin_trajectory.hpp"

#include <Eigen/SVD>
#include <cmath>
#include <functional>
#include <stdexcept>

namespace litamin2::sim {
namespace {

/// Integrates a drive from a curvature profile kappa(s) and a height profile z(s), sampled every
/// speed * 0.1 m, and expresses it relative to its first pose.
std::vector<Eigen::Isometry3d> integrate(double length, double speed,
                                         const std::function<double(double)>& kappa,
                                         const std::function<double(double)>& height) {
  const double ds = speed * 0.1;
  const int n = static_cast<int>(std::round(length / ds));
  std::vector<Eigen::Isometry3d> poses;
  double x = 0, y = 0, yaw = 0;
  const int sub = 20;
  for (int i = 0; i < n; ++i) {
    const double s = i * ds;
    const double dz = (height(s + 0.5) - height(s - 0.5));
    const double pitch = -std::atan(dz);  // nose up when climbing (rotation about y is -pitch)
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(x, y, height(s) - height(0));
    T.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                  Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()))
                     .toRotationMatrix();
    poses.push_back(T);
    for (int k = 0; k < sub; ++k) {
      const double h = ds / sub;
      const double sm = s + (k + 0.5) * h;
      const double yaw_mid = yaw + 0.5 * h * kappa(sm);
      x += h * std::cos(yaw_mid);
      y += h * std::sin(yaw_mid);
      yaw += h * kappa(sm);
    }
  }
  const Eigen::Isometry3d inv0 = poses.front().inverse();
  for (auto& p : poses) p = inv0 * p;
  return poses;
}

}  // namespace

std::vector<Eigen::Isometry3d> builtin_trajectory(const std::string& name) {
  if (name == "loop") {
    // Rounded rectangle: straight 86 m, quarter turn r=12, straight 31 m (with an S-bend),
    // quarter turn, straight 86 m, quarter turn, straight 31 m, quarter turn.
    const double r = 12.0, arc = 0.5 * M_PI * r, a = 86.0, b = 31.0;
    const double segs[8] = {a, arc, b, arc, a, arc, b, arc};
    double total = 0;
    for (double s : segs) total += s;
    auto kappa = [=](double s) {
      double acc = 0;
      for (int i = 0; i < 8; ++i) {
        if (s < acc + segs[i] || i == 7) {
          if (i % 2 == 1) return 1.0 / r;
          // S-bends (+ - - + curvature: no net heading or lateral change) on both long
          // straights, so the loop closes exactly.
          if (i == 0 || i == 4) {
            const double u = s - acc;
            if (u > 20 && u < 32) return 0.02;
            if (u > 32 && u < 56) return -0.02;
            if (u > 56 && u < 68) return 0.02;
          }
          return 0.0;
        }
        acc += segs[i];
      }
      return 0.0;
    };
    auto height = [=](double s) { return 1.5 * std::sin(2.0 * M_PI * s / total); };
    return integrate(total, 8.0, kappa, height);
  }
  if (name == "highway") {
    auto kappa = [](double s) { return 0.0015 * std::sin(2.0 * M_PI * s / 400.0); };
    auto height = [](double s) { return 3.0 * std::sin(2.0 * M_PI * s / 900.0); };
    return integrate(600.0, 25.0, kappa, height);
  }
  throw std::invalid_argument("unknown built-in trajectory '" + name + "' (use loop or highway)");
}

std::vector<std::string> builtin_trajectory_names() {
  return {"loop", "highway"};
}

Eigen::Isometry3d kitti_default_velo_to_cam() {
  Eigen::Matrix<double, 3, 4> m;
  m << 4.276802385584e-04, -9.999672484946e-01, -8.084491683471e-03, -1.198459927713e-02,
      -7.210626507497e-03, 8.081198471645e-03, -9.999413164504e-01, -5.403984729748e-02,
      9.999738645903e-01, 4.859485810390e-04, -7.206933692422e-03, -2.921968648686e-01;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = m.leftCols<3>();
  T.translation() = m.col(3);
  return orthonormalized(T);
}

Eigen::Isometry3d orthonormalized(const Eigen::Isometry3d& T) {
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(T.linear(), Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d R = svd.matrixU() * svd.matrixV().transpose();
  if (R.determinant() < 0) {
    Eigen::Matrix3d U = svd.matrixU();
    U.col(2) *= -1.0;
    R = U * svd.matrixV().transpose();
  }
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = R;
  out.translation() = T.translation();
  return out;
}

}  // namespace litamin2::sim

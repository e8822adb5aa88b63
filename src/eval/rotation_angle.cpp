#include "litamin2/eval/rotation_angle.hpp"

#include <algorithm>
#include <cmath>

namespace litamin2::eval {

double rotation_angle_between(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  // m = a^T * b with explicit sums so that m is exactly symmetric when a == b.
  double m[3][3];
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      m[i][j] = a(0, i) * b(0, j) + a(1, i) * b(1, j) + a(2, i) * b(2, j);
    }
  }
  const double cos_angle = std::clamp(0.5 * (m[0][0] + m[1][1] + m[2][2] - 1.0), -1.0, 1.0);
  const double vx = m[2][1] - m[1][2];
  const double vy = m[0][2] - m[2][0];
  const double vz = m[1][0] - m[0][1];
  const double sin_angle = 0.5 * std::sqrt(vx * vx + vy * vy + vz * vz);
  return std::atan2(sin_angle, cos_angle);
}

double rotation_angle(const Eigen::Matrix3d& r) {
  return rotation_angle_between(Eigen::Matrix3d::Identity(), r);
}

}  // namespace litamin2::eval

#include "litamin2/core/motion_model.hpp"

#include <algorithm>

namespace litamin2 {

Eigen::Isometry3d scaled_motion(const Eigen::Isometry3d& motion, double s) {
  const Eigen::AngleAxisd rotation(motion.linear());
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = Eigen::AngleAxisd(s * rotation.angle(), rotation.axis()).toRotationMatrix();
  out.translation() = s * motion.translation();
  return out;
}

double interval_ratio(double interval, double previous_interval, double max_ratio) {
  if (!(interval > 0.0) || !(previous_interval > 0.0)) return 1.0;
  return std::min(interval / previous_interval, max_ratio);
}

}  // namespace litamin2

#include "litamin2/sim/continuous_trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace litamin2::sim {

Eigen::Isometry3d interpolate_pose(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b,
                                   double s) {
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  const Eigen::Quaterniond qa(a.linear()), qb(b.linear());
  if (s >= 0.0 && s <= 1.0) {
    out.linear() = qa.slerp(s, qb).toRotationMatrix();
  } else {
    // Extrapolation: apply the relative rotation's angle-axis scaled by s.
    const Eigen::AngleAxisd rel(qa.inverse() * qb);
    out.linear() = (qa * Eigen::Quaterniond(Eigen::AngleAxisd(rel.angle() * s, rel.axis())))
                       .toRotationMatrix();
  }
  out.translation() = a.translation() + s * (b.translation() - a.translation());
  return out;
}

ContinuousTrajectory::ContinuousTrajectory(std::vector<Eigen::Isometry3d> poses,
                                           std::vector<double> times)
    : poses_(std::move(poses)), times_(std::move(times)) {
  if (poses_.empty()) throw std::invalid_argument("ContinuousTrajectory: no poses");
  if (poses_.size() != times_.size()) {
    throw std::invalid_argument("ContinuousTrajectory: " + std::to_string(poses_.size()) +
                                " poses but " + std::to_string(times_.size()) + " times");
  }
  for (std::size_t i = 0; i < times_.size(); ++i) {
    if (!std::isfinite(times_[i]) || (i > 0 && !(times_[i] > times_[i - 1]))) {
      throw std::invalid_argument(
          "ContinuousTrajectory: times must be finite and strictly "
          "increasing (sample " +
          std::to_string(i) + ")");
    }
  }
}

namespace {
std::vector<double> regular_times(std::size_t n, double period) {
  if (!(period > 0.0)) throw std::invalid_argument("ContinuousTrajectory: period must be > 0");
  std::vector<double> t(n);
  for (std::size_t i = 0; i < n; ++i) t[i] = static_cast<double>(i) * period;
  return t;
}
}  // namespace

ContinuousTrajectory::ContinuousTrajectory(std::vector<Eigen::Isometry3d> poses, double period)
    : ContinuousTrajectory(poses, regular_times(poses.size(), period)) {}

Eigen::Isometry3d ContinuousTrajectory::pose_at(double t) const {
  const std::size_t n = poses_.size();
  if (n == 1) return poses_[0];
  // Segment [i, i + 1] containing t (the first or last one outside the samples).
  const auto it = std::upper_bound(times_.begin(), times_.end(), t);
  std::size_t i = it == times_.begin() ? 0 : static_cast<std::size_t>(it - times_.begin()) - 1;
  i = std::min(i, n - 2);
  if (t == times_[i]) return poses_[i];
  if (t == times_[i + 1]) return poses_[i + 1];
  const double s = (t - times_[i]) / (times_[i + 1] - times_[i]);
  return interpolate_pose(poses_[i], poses_[i + 1], s);
}

}  // namespace litamin2::sim

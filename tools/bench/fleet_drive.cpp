#include "fleet_drive.hpp"

#include <cmath>

namespace litamin2::bench {
namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kLane = 2.0;
constexpr double kSensorHeight = 1.7;

Eigen::Isometry3d small_motion(double tx, double ty, double tz, double roll, double pitch,
                               double yaw) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  t.translation() = Eigen::Vector3d(tx, ty, tz);
  return t;
}

}  // namespace

FleetVehicleDrive::FleetVehicleDrive(const FleetDriveConfig& config, unsigned seed)
    : config_(config), rng_(seed) {
  std::uniform_int_distribution<int> node(1, config.blocks - 1), dir(0, 3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  ix_ = node(rng_);
  iy_ = node(rng_);
  const int d = dir(rng_);
  dx_ = d == 0 ? 1 : d == 1 ? -1 : 0;
  dy_ = d == 2 ? 1 : d == 3 ? -1 : 0;
  yaw_bias_ = u(rng_) * config.yaw_bias_deg * kDeg;
}

Eigen::Isometry3d FleetVehicleDrive::pose_at() const {
  const double b = config_.block_size;
  const Eigen::Vector2d dir(dx_, dy_), right(dy_, -dx_);
  const Eigen::Vector2d p = Eigen::Vector2d(ix_ * b, iy_ * b) + dir * s_ + right * kLane;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() =
      Eigen::AngleAxisd(std::atan2(dy_, dx_), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const double z = 0.4 * std::sin(0.013 * p.x()) * std::cos(0.011 * p.y()) + kSensorHeight;
  pose.translation() = Eigen::Vector3d(p.x(), p.y(), z);
  return pose;
}

void FleetVehicleDrive::next() {
  if (started_) {
    s_ += config_.spacing;
    if (s_ >= config_.block_size) {
      // At the next intersection: go on, or turn, staying inside the grid.
      s_ -= config_.block_size;
      ix_ += dx_;
      iy_ += dy_;
      std::uniform_real_distribution<double> u(0.0, 1.0);
      for (int attempt = 0; attempt < 8; ++attempt) {
        const double c = u(rng_);
        int ndx = dx_, ndy = dy_;
        if (c >= 0.5 && c < 0.75) ndx = -dy_, ndy = dx_;  // left
        if (c >= 0.75) ndx = dy_, ndy = -dx_;             // right
        if (attempt == 7) ndx = -dx_, ndy = -dy_;         // dead end: turn back
        const int nx = ix_ + ndx, ny = iy_ + ndy;
        if (nx < 0 || ny < 0 || nx > config_.blocks || ny > config_.blocks) continue;
        dx_ = ndx;
        dy_ = ndy;
        break;
      }
    }
  }
  const Eigen::Isometry3d previous = truth_;
  truth_ = pose_at();
  if (!started_) {
    started_ = true;
    first_ = truth_;
    odometry_ = Eigen::Isometry3d::Identity();
    return;
  }
  std::normal_distribution<double> n(0.0, 1.0);
  const double tn = config_.translation_noise, rn = config_.rotation_noise_deg * kDeg;
  const Eigen::Isometry3d noise =
      small_motion(tn * n(rng_), tn * n(rng_), tn * n(rng_) * 0.5, rn * n(rng_) * 0.3,
                   rn * n(rng_) * 0.3, rn * n(rng_) + yaw_bias_);
  odometry_ = odometry_ * (previous.inverse() * truth_) * noise;
}

}  // namespace litamin2::bench

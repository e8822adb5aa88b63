#include "litamin2/sim/sensor_mount.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>
#include <string>

namespace litamin2::sim {

Eigen::Matrix3d SensorMount::rotation() const {
  constexpr double kDeg = M_PI / 180.0;
  return (Eigen::AngleAxisd(yaw_deg * kDeg, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(pitch_deg * kDeg, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll_deg * kDeg, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

bool SensorMount::is_identity() const {
  return roll_deg == 0.0 && pitch_deg == 0.0 && yaw_deg == 0.0;
}

void SensorMount::validate() const {
  auto check = [](double v, double limit, const char* name) {
    if (!std::isfinite(v) || std::abs(v) > limit) {
      throw std::invalid_argument(std::string("sensor mount: ") + name + " " + std::to_string(v) +
                                  " deg is outside +-" + std::to_string(limit) + " deg");
    }
  };
  check(roll_deg, 30.0, "roll");
  check(pitch_deg, 30.0, "pitch");
  check(yaw_deg, 180.0, "yaw");
}

}  // namespace litamin2::sim

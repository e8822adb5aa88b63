#include "litamin2/core/deskew.hpp"

#include "litamin2/core/config_error.hpp"
#include "litamin2/core/so3.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace litamin2 {
namespace {

/// Grid of deskew(): Exp(t xi) is evaluated at multiples of this time, seconds.
constexpr double kTimeStep = 1e-4;
/// Points per task of deskew(); fixed, so the work split does not depend on the threads.
constexpr std::size_t kChunk = 16384;

void require(bool ok, const std::string& key, double value, const std::string& rule) {
  if (ok) return;
  throw ConfigError("deskew." + key + ": " + std::to_string(value) + " is invalid (" + rule + ")");
}

/// Coefficients of SE(3)'s V = I + a [w]x + b [w]x^2 for a rotation vector of angle theta.
void v_coefficients(double theta, double& a, double& b) {
  if (theta < 1e-4) {
    const double t2 = theta * theta;
    a = 0.5 - t2 / 24.0;
    b = 1.0 / 6.0 - t2 / 120.0;
    return;
  }
  const double t2 = theta * theta;
  a = (1.0 - std::cos(theta)) / t2;
  b = (theta - std::sin(theta)) / (t2 * theta);
}

}  // namespace

void validate(const DeskewConfig& c) {
  const AzimuthTiming& a = c.azimuth;
  require(std::isfinite(a.period_s) && a.period_s > 0.0 && a.period_s <= kMaxPointTime,
          "azimuth.period_s", a.period_s, "seconds, in (0, 1]");
  require(std::isfinite(a.start_deg) && std::abs(a.start_deg) <= 360.0, "azimuth.start_deg",
          a.start_deg, "degrees, within [-360, 360]");
  require(c.passes == 1 || c.passes == 2, "passes", c.passes,
          "1: the predicted motion only, 2: again with the registered motion");
  validate(c.sweep_motion);
}

Twist twist_from_motion(const Eigen::Isometry3d& motion, double seconds) {
  if (!(seconds > 0.0) || !std::isfinite(seconds))
    throw std::invalid_argument("twist_from_motion: the interval must be positive, got " +
                                std::to_string(seconds) + " s");
  // SE(3) logarithm: w = log(R), v = V^-1 t with V^-1 = I - [w]x / 2 + c [w]x^2.
  const Eigen::AngleAxisd rotation(Eigen::Quaterniond(motion.linear()).normalized());
  const double theta = rotation.angle();
  const Eigen::Vector3d w = theta * rotation.axis();
  double c = 1.0 / 12.0 + theta * theta / 720.0;
  if (theta >= 1e-4) {
    c = (1.0 - theta * std::sin(theta) / (2.0 * (1.0 - std::cos(theta)))) / (theta * theta);
  }
  const Eigen::Matrix3d W = skew(w);
  const Eigen::Vector3d v =
      (Eigen::Matrix3d::Identity() - 0.5 * W + c * W * W) * motion.translation();
  Twist twist;
  twist.angular = w / seconds;
  twist.linear = v / seconds;
  return twist;
}

Eigen::Isometry3d motion_after(const Twist& twist, double seconds) {
  // SE(3) exponential: R = exp([w]x), t = V v.
  const Eigen::Vector3d w = seconds * twist.angular;
  const Eigen::Vector3d v = seconds * twist.linear;
  double a = 0.0, b = 0.0;
  v_coefficients(w.norm(), a, b);
  const Eigen::Matrix3d W = skew(w);
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = so3_exp(w);
  out.translation() = (Eigen::Matrix3d::Identity() + a * W + b * W * W) * v;
  return out;
}

void deskew(const PointCloud& scan, const Twist& twist, PointCloud& out) {
  deskew(scan, scan.times, twist, out);
}

void deskew(const PointCloud& scan, const std::vector<float>& times, const Twist& twist,
            PointCloud& out) {
  if (&scan == &out) throw std::invalid_argument("deskew: the output may not be the input");
  if (times.size() != scan.size())
    throw std::invalid_argument("deskew: " + std::to_string(times.size()) + " times for " +
                                std::to_string(scan.size()) + " points");
  for (const float t : times) {
    if (!std::isfinite(t) || std::abs(static_cast<double>(t)) > kMaxPointTime)
      throw std::invalid_argument("deskew: a point time of " + std::to_string(t) +
                                  " s is not finite or beyond 1 s");
  }
  const std::size_t n = scan.size();
  out.points.resize(n);
  out.intensities = scan.intensities;
  out.times.clear();
  if (n == 0) return;

  // Exp(t xi) at the grid times k * kTimeStep covering the scan's times.
  float lo = times[0], hi = times[0];
  for (const float t : times) {
    lo = std::min(lo, t);
    hi = std::max(hi, t);
  }
  const long first = std::lround(static_cast<double>(lo) / kTimeStep);
  const long last = std::lround(static_cast<double>(hi) / kTimeStep);
  std::vector<Eigen::Matrix3f> rotations(static_cast<std::size_t>(last - first + 1));
  std::vector<Eigen::Vector3f> translations(rotations.size());
  for (long k = first; k <= last; ++k) {
    const Eigen::Isometry3d m = motion_after(twist, static_cast<double>(k) * kTimeStep);
    rotations[static_cast<std::size_t>(k - first)] = m.linear().cast<float>();
    translations[static_cast<std::size_t>(k - first)] = m.translation().cast<float>();
  }
  const Eigen::Vector3f w = twist.angular.cast<float>();
  const Eigen::Vector3f v = twist.linear.cast<float>();

  // p' = Exp(t_k xi) Exp(d xi) p with d = t - t_k, |d| <= kTimeStep / 2, and
  // Exp(d xi) p = p + d (w x p + v) to first order.
  auto range = [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const double t = times[i];
      const long k = std::lround(t / kTimeStep);
      const float d = static_cast<float>(t - static_cast<double>(k) * kTimeStep);
      const std::size_t slot = static_cast<std::size_t>(k - first);
      const Eigen::Vector3f& p = scan.points[i];
      out.points[i] = rotations[slot] * (p + d * (w.cross(p) + v)) + translations[slot];
    }
  };
  if (n <= kChunk) {
    range(0, n);
    return;
  }
  const std::size_t chunks = (n + kChunk - 1) / kChunk;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks, 1),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t c = r.begin(); c < r.end(); ++c)
                        range(c * kChunk, std::min(n, (c + 1) * kChunk));
                    });
}

void times_from_azimuth(const PointCloud& scan, const AzimuthTiming& timing,
                        std::vector<float>& times) {
  times.resize(scan.size());
  const double start = timing.start_deg * M_PI / 180.0;
  const double turn = 2.0 * M_PI;
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const Eigen::Vector3f& p = scan.points[i];
    const double azimuth = std::atan2(static_cast<double>(p.y()), static_cast<double>(p.x()));
    double turned = timing.clockwise ? start - azimuth : azimuth - start;
    turned = std::fmod(turned, turn);
    if (turned < 0.0) turned += turn;
    // fmod can return `turn` itself after the correction of a tiny negative value.
    if (turned >= turn) turned = 0.0;
    times[i] = static_cast<float>(timing.period_s * turned / turn);
  }
}

}  // namespace litamin2

#include "fleet_world.hpp"

#include <cmath>

namespace litamin2::bench {
namespace {

constexpr double kVoxel = 3.0;
constexpr double kCell = 10.0;

}  // namespace

FleetWorld::FleetWorld(const FleetWorldConfig& config) : config_(config) {
  std::mt19937 rng(config.seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double b = config.block_size;
  // Buildings along the four sides of every block, set back from the street's centre line.
  for (int i = 0; i < config.blocks; ++i) {
    for (int j = 0; j < config.blocks; ++j) {
      const Eigen::Vector2d lo(i * b, j * b), hi((i + 1) * b, (j + 1) * b);
      for (int side = 0; side < 4; ++side) {
        const double setback = 7.0 + 5.0 * u(rng);
        // The side runs from p0 to p1 inside the block, normal pointing to the street.
        Eigen::Vector2d p0, p1, n;
        if (side == 0)
          p0 = {lo.x(), lo.y() + setback}, p1 = {hi.x(), lo.y() + setback}, n = {0, -1};
        if (side == 1) p0 = {hi.x() - setback, lo.y()}, p1 = {hi.x() - setback, hi.y()}, n = {1, 0};
        if (side == 2) p0 = {lo.x(), hi.y() - setback}, p1 = {hi.x(), hi.y() - setback}, n = {0, 1};
        if (side == 3)
          p0 = {lo.x() + setback, lo.y()}, p1 = {lo.x() + setback, hi.y()}, n = {-1, 0};
        const Eigen::Vector2d dir = (p1 - p0).normalized();
        double s = 12.0 + 6.0 * u(rng);  // keep the corners open
        const double length = (p1 - p0).norm() - 12.0;
        while (s < length) {
          const double width = std::min(8.0 + 17.0 * u(rng), length - s);
          // Each building its own setback and a turn of up to +-12 degrees, so that no two
          // streets line up alike (a grid of parallel walls fits any other street along the
          // walls' normals).
          const double depth = 5.0 * u(rng);
          const double turn = (u(rng) - 0.5) * 24.0 * M_PI / 180.0;
          const Eigen::Vector2d centre = p0 + dir * (s + width / 2) - n * depth;
          const Eigen::Rotation2Dd rot(turn);
          const Eigen::Vector2d d2 = rot * dir;
          add_facade(centre - d2 * (width / 2), centre + d2 * (width / 2), 4.0 + 16.0 * u(rng),
                     rot * n);
          if (u(rng) < 0.5) {  // a side wall, seen at the gaps
            const Eigen::Vector2d corner = centre + d2 * (width / 2);
            add_facade(corner - (rot * n) * 8.0, corner, 4.0 + 8.0 * u(rng), d2);
          }
          s += width + 2.0 + 8.0 * u(rng) * (u(rng) < 0.5);
        }
        // Poles and trees at the kerb, 4.5 m from the centre line.
        for (double t = 5.0 + 20.0 * u(rng); t < b - 5.0; t += 12.0 + 20.0 * u(rng)) {
          Eigen::Vector2d at = p0 + dir * t;
          at += n * (setback - 4.5);
          add_pole(at, u(rng) < 0.5 ? 6.0 : 3.0);
        }
      }
    }
  }
  add_ground();
}

double FleetWorld::ground_z(double x, double y) const {
  return 0.4 * std::sin(0.013 * x) * std::cos(0.011 * y);
}

void FleetWorld::add_facade(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double height,
                            const Eigen::Vector2d& normal) {
  const Eigen::Vector2d dir = (b - a).normalized();
  const double width = (b - a).norm();
  for (double s = 0.0; s < width; s += kVoxel) {
    const double w = std::min(kVoxel, width - s);
    const Eigen::Vector2d c = a + dir * (s + w / 2);
    for (double z = 0.0; z < height; z += kVoxel) {
      const double h = std::min(kVoxel, height - z);
      Voxel v;
      v.d.mean = Eigen::Vector3d(c.x(), c.y(), ground_z(c.x(), c.y()) + z + h / 2);
      const Eigen::Vector3d along(dir.x(), dir.y(), 0.0), up(0, 0, 1), n(normal.x(), normal.y(), 0);
      v.d.cov = along * along.transpose() * (w * w / 12) + up * up.transpose() * (h * h / 12) +
                n * n.transpose() * 4e-4;
      v.d.count = static_cast<int>(20 + 10 * w * h);
      v.normal = n;
      voxels_.push_back(v);
    }
  }
}

void FleetWorld::add_pole(const Eigen::Vector2d& at, double height) {
  for (double z = 0.0; z < height; z += kVoxel) {
    const double h = std::min(kVoxel, height - z);
    Voxel v;
    v.d.mean = Eigen::Vector3d(at.x(), at.y(), ground_z(at.x(), at.y()) + z + h / 2);
    v.d.cov = Eigen::Vector3d(0.012, 0.012, h * h / 12).asDiagonal();
    v.d.count = 15;
    voxels_.push_back(v);
  }
}

void FleetWorld::add_ground() {
  const double extent = config_.blocks * config_.block_size + 40.0;
  for (double x = -40.0; x < extent; x += kVoxel) {
    for (double y = -40.0; y < extent; y += kVoxel) {
      Voxel v;
      const double cx = x + kVoxel / 2, cy = y + kVoxel / 2;
      v.d.mean = Eigen::Vector3d(cx, cy, ground_z(cx, cy));
      v.d.cov = Eigen::Vector3d(0.75, 0.75, 4e-4).asDiagonal();
      v.d.count = 60;
      v.ground = true;
      voxels_.push_back(v);
    }
  }
  for (std::uint32_t i = 0; i < voxels_.size(); ++i) {
    const Eigen::Vector3d& m = voxels_[i].d.mean;
    cells_[cell_key(static_cast<std::int64_t>(std::floor(m.x() / kCell)),
                    static_cast<std::int64_t>(std::floor(m.y() / kCell)))]
        .push_back(i);
  }
}

std::vector<Distribution> FleetWorld::patch(const Eigen::Isometry3d& sensor,
                                            std::mt19937& rng) const {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, config_.mean_noise);
  const Eigen::Vector3d o = sensor.translation();
  const Eigen::Isometry3d to_sensor = sensor.inverse();
  const Eigen::Matrix3d r = to_sensor.linear();
  const double r2 = config_.range * config_.range, g2 = config_.ground_range * config_.ground_range;
  std::vector<Distribution> out;
  const auto x0 = static_cast<std::int64_t>(std::floor((o.x() - config_.range) / kCell));
  const auto x1 = static_cast<std::int64_t>(std::floor((o.x() + config_.range) / kCell));
  const auto y0 = static_cast<std::int64_t>(std::floor((o.y() - config_.range) / kCell));
  const auto y1 = static_cast<std::int64_t>(std::floor((o.y() + config_.range) / kCell));
  for (std::int64_t x = x0; x <= x1; ++x) {
    for (std::int64_t y = y0; y <= y1; ++y) {
      const auto it = cells_.find(cell_key(x, y));
      if (it == cells_.end()) continue;
      for (std::uint32_t i : it->second) {
        const Voxel& v = voxels_[i];
        const Eigen::Vector3d d = v.d.mean - o;
        const double dist2 = d.x() * d.x() + d.y() * d.y();
        if (dist2 > (v.ground ? g2 : r2)) continue;
        if (v.normal.squaredNorm() > 0 && v.normal.dot(d) >= 0) continue;  // faces away
        if (u(rng) < config_.dropout) continue;
        Distribution s;
        s.mean = to_sensor * v.d.mean + Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
        s.cov = r * v.d.cov * r.transpose();
        s.count = v.d.count;
        out.push_back(s);
      }
    }
  }
  return out;
}

}  // namespace litamin2::bench

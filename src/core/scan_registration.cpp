#include "litamin2/core/scan_registration.hpp"

#include "litamin2/core/stopwatch.hpp"

#include <chrono>

namespace litamin2 {
namespace {

bool moved_beyond(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b,
                  const RegistrationConfig& config) {
  const Eigen::Isometry3d delta = a.inverse() * b;
  return delta.translation().norm() > config.regrid_translation ||
         Eigen::AngleAxisd(delta.linear()).angle() > config.regrid_rotation_deg * M_PI / 180.0;
}

}  // namespace

ScanRegistration register_scan(const PointCloud& scan, Voxelizer& voxelizer, const VoxelMap& map,
                               const CorrespondenceSearch& search, const Eigen::Isometry3d& initial,
                               const RegistrationConfig& config) {
  ScanRegistration out;
  Eigen::Isometry3d grid_pose = initial;
  for (int pass = 0; pass <= config.max_regrids; ++pass) {
    auto start = std::chrono::steady_clock::now();
    out.source = voxelizer.voxelize(scan, grid_pose);
    ++out.voxelizations;
    out.voxelize_ms += elapsed_ms(start);

    start = std::chrono::steady_clock::now();
    out.result = register_distributions(out.source, map, search, grid_pose, config);
    out.register_ms += elapsed_ms(start);
    if (!out.result.valid || !moved_beyond(grid_pose, out.result.pose, config)) break;
    grid_pose = out.result.pose;
  }
  return out;
}

}  // namespace litamin2

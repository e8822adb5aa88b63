#include "litamin2/core/scan_registration.hpp"

#include "litamin2/core/stopwatch.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace litamin2 {

RegridLoop::RegridLoop(const RegistrationConfig& config, const Eigen::Isometry3d& initial)
    : config_(config),
      grid_pose_(initial),
      previous_correction_(std::numeric_limits<double>::infinity()) {}

bool RegridLoop::next(const RegistrationResult& result) {
  const int pass = passes_++;
  result_ = result;
  if (!result.valid || pass >= config_.max_regrids) return false;
  const double moved = regrid_correction(grid_pose_, result.pose, config_);
  if (moved <= 1.0) return false;
  // From the second re-grid on, a correction that did not shrink ends the loop at the previous
  // pass's result, whose pose this pass's grid was cut at (so the scan's distributions and grid
  // voxels stay those of the returned pose). The first re-grid is always made: it is what
  // removes the bias of the predicted grid.
  if (config_.regrid_contraction > 0.0 && pass >= 2 &&
      moved > config_.regrid_contraction * previous_correction_) {
    result_ = previous_;
    stopped_ = true;
    return false;
  }
  previous_ = result;
  previous_correction_ = moved;
  grid_pose_ = result.pose;
  return true;
}

ScanRegistration register_scan(const PointCloud& scan, Voxelizer& voxelizer, const VoxelMap& map,
                               const CorrespondenceSearch& search, const Eigen::Isometry3d& initial,
                               const RegistrationConfig& config) {
  ScanRegistration out;
  RegridLoop loop(config, initial);
  for (;;) {
    auto start = std::chrono::steady_clock::now();
    out.grid_pose = loop.grid_pose();
    out.source = voxelizer.voxelize(scan, out.grid_pose);
    ++out.voxelizations;
    out.voxelize_ms += elapsed_ms(start);

    start = std::chrono::steady_clock::now();
    const RegistrationResult result =
        register_distributions(out.source, map, search, out.grid_pose, config);
    out.register_ms += elapsed_ms(start);
    if (!loop.next(result)) break;
  }
  out.result = loop.result();
  out.regrid_stopped = loop.stopped();
  return out;
}

}  // namespace litamin2

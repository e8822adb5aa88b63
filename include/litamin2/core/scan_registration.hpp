#pragma once
/// Registration of a raw scan to the map: voxelise the scan in the map's grid at the pose
/// estimate, run Newton (registration.hpp), and voxelise again at the new estimate while it
/// moved by more than the regrid tolerances (RegistrationConfig).

#include "litamin2/core/registration.hpp"
#include "litamin2/core/voxelizer.hpp"

namespace litamin2 {

struct ScanRegistration {
  /// The last registration's result.
  RegistrationResult result;
  /// Distributions of the scan, sensor frame, cut in the grid of the final estimate's
  /// predecessor.
  std::vector<Distribution> source;
  /// Number of times the scan was voxelised.
  int voxelizations = 0;
  /// Time spent voxelising, milliseconds.
  double voxelize_ms = 0.0;
  /// Time spent in Newton iterations, milliseconds.
  double register_ms = 0.0;
};

ScanRegistration register_scan(const PointCloud& scan, Voxelizer& voxelizer, const VoxelMap& map,
                               const CorrespondenceSearch& search, const Eigen::Isometry3d& initial,
                               const RegistrationConfig& config);

}  // namespace litamin2

#pragma once
/// Everything a LiTAMIN2 tracker is configured by, in one struct, and its validation (read from
/// YAML by config/tracker_config_yaml.hpp).

#include "litamin2/core/config_error.hpp"
#include "litamin2/core/deskew.hpp"
#include "litamin2/core/registration_config.hpp"
#include "litamin2/core/voxel_map.hpp"
#include "litamin2/core/voxelizer.hpp"

namespace litamin2 {

struct KeyframeConfig {
  /// A frame that moved this far from the last keyframe becomes a keyframe, metres.
  double distance = 2.0;
  /// ... or that turned this much, degrees.
  double angle_deg = 5.0;
};

struct TrackerConfig {
  /// Scan voxelisation; the map uses the same voxel size, point limits and regularisation.
  VoxelizerConfig voxelizer;
  /// Map extent.
  VoxelMapConfig map;
  /// The solver.
  RegistrationConfig registration;
  /// When the map is updated.
  KeyframeConfig keyframe;
  /// Motion compensation within the sweep (Tracker::process with a SweepTiming).
  DeskewConfig deskew;
};

/// Throws ConfigError on the first invalid value.
void validate(const TrackerConfig& config);

}  // namespace litamin2

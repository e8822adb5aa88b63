#pragma once
/// Everything a LiTAMIN2 tracker is configured by, in one struct, with YAML load and save.

#include "litamin2/core/config_error.hpp"
#include "litamin2/core/registration_config.hpp"
#include "litamin2/core/voxel_map.hpp"
#include "litamin2/core/voxelizer.hpp"

#include <stdexcept>
#include <string>

namespace YAML {
class Node;
}

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
};

/// Reads a tracker config from a YAML mapping; absent keys keep their defaults, unknown keys
/// and invalid values throw ConfigError.
TrackerConfig tracker_config_from_yaml(const YAML::Node& node);
/// Reads a YAML file (the whole file, or its `tracker:` section if it has one).
TrackerConfig load_tracker_config(const std::string& path);
/// The full config as YAML (every key, so a run's config.yaml reproduces it).
std::string tracker_config_to_yaml(const TrackerConfig& config);
/// Throws ConfigError on the first invalid value.
void validate(const TrackerConfig& config);

}  // namespace litamin2

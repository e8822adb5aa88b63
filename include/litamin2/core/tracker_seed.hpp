#pragma once
/// Where a tracker continues a stream that another tracker had (a stream handed over between
/// daemons, daemon/stream_handover.hpp): the other tracker's last keyframes, known by their
/// distributions and poses, become the map the next scan is registered to, and the next scan
/// is predicted at a given pose with a given motion per frame. The scan is then registered
/// against the same surfaces the other tracker used instead of starting a new map at a
/// predicted pose, so that the prediction's error over the handover gap is corrected by the
/// first registration instead of being carried on as an offset.

#include "litamin2/core/distribution.hpp"

#include <Eigen/Geometry>
#include <vector>

namespace litamin2 {

/// One keyframe of the map a continued tracker starts with.
struct SeedKeyframe {
  /// Sensor pose in the tracker's frame (the frame of Tracker::FrameResult::pose).
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  /// Voxel edge the distributions were computed on: a keyframe whose voxel size is not the
  /// tracker's map's is not used.
  double voxel_size = 0.0;
  /// The keyframe scan's distributions, sensor frame.
  std::vector<Distribution> distributions;
};

struct TrackerSeed {
  /// The map, oldest keyframe first (the far voxels are dropped around the last one, as the
  /// tracker's own map is). May be empty: the first scan then starts the map at `predicted`.
  std::vector<SeedKeyframe> keyframes;
  /// The sensor pose predicted for the first scan, tracker frame.
  Eigen::Isometry3d predicted = Eigen::Isometry3d::Identity();
  /// The sensor's motion per frame (the constant-velocity model), identity when unknown.
  Eigen::Isometry3d velocity = Eigen::Isometry3d::Identity();
  /// The interval `velocity` spans, seconds (deskew's first pass uses it); 0 when unknown.
  double interval_s = 0.0;
};

}  // namespace litamin2

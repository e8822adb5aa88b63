#pragma once
/// What the aggregator publishes, in the mapper's types, and how it is read off the mapper:
/// per-stream corrected keyframe poses and the global map's summary. The DDS node turns them
/// into litamin2/msg/KeyframePoses and MapSummary; export writes the same poses to files.

#include "litamin2/mapping/mapper.hpp"

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

namespace litamin2::aggregator {

struct StreamPoses {
  std::string stream;
  /// The stream whose odometry frame the poses are in (the first stream of its loop group).
  std::string anchor;
  /// anchor is the map's anchor stream: the poses are in the shared map frame.
  bool in_map_frame = false;
  /// corrected = correction * odometry pose, for the stream's latest keyframe.
  Eigen::Isometry3d correction = Eigen::Isometry3d::Identity();
  struct Entry {
    std::uint64_t id = 0;
    Stamp stamp;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  };
  /// Every keyframe of the stream, by id.
  std::vector<Entry> keyframes;
};

struct MapSummary {
  /// The stream whose odometry frame is the map frame ("" when there is no keyframe).
  std::string anchor;
  double voxel_size = 0.0;
  std::size_t voxels = 0;
  std::size_t keyframes = 0;
  std::size_t streams = 0;
  std::size_t loops = 0;
  std::size_t optimizations = 0;
  /// Bounding box of the voxel means (zero when there are none).
  Eigen::Vector3d min_bound = Eigen::Vector3d::Zero();
  Eigen::Vector3d max_bound = Eigen::Vector3d::Zero();
  /// At most max_means voxel means, evenly decimated in the global map's order.
  std::vector<Eigen::Vector3f> means;
};

/// Corrected poses of every stream, ordered by stream id.
std::vector<StreamPoses> all_stream_poses(const mapping::Mapper& mapper);
/// Corrected poses of the given streams (unknown ones are skipped).
std::vector<StreamPoses> stream_poses(const mapping::Mapper& mapper,
                                      const std::vector<std::string>& streams);

/// The summary of `global_map` (mapper.global_map(), passed in so that it is built once).
MapSummary map_summary(const mapping::Mapper& mapper, const std::vector<Distribution>& global_map,
                       std::size_t max_means);

}  // namespace litamin2::aggregator

#pragma once
/// Place recognition for a new keyframe: candidates from its group's nearest keyframe by pose
/// estimate and from the place descriptors, each verified by LiTAMIN2 registration to a submap
/// of the candidate and its neighbours (loop_verifier.hpp); the first verified one is the loop.

#include "litamin2/core/keyframe.hpp"
#include "litamin2/core/voxel_map.hpp"
#include "litamin2/mapping/loop_edge.hpp"
#include "litamin2/mapping/mapper_config.hpp"
#include "litamin2/mapping/mapper_stats.hpp"
#include "litamin2/mapping/place_descriptor.hpp"
#include "litamin2/mapping/stream_groups.hpp"

#include <Eigen/Geometry>
#include <map>
#include <optional>
#include <utility>

namespace litamin2::mapping {

/// A keyframe as the mapper holds it.
struct MapperEntry {
  Keyframe keyframe;
  PlaceDescriptor descriptor;
  /// Current estimate of the sensor pose in the frame of the stream's group's anchor.
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
};
using MapperEntries = std::map<KeyframeKey, MapperEntry>;

class LoopDetector {
 public:
  /// `config` must outlive the detector.
  explicit LoopDetector(const MapperConfig& config) : config_(config) {}

  /// The loop of `query` (one of `entries`) with the keyframes present, if a candidate is
  /// verified; counts candidates, verified and rejected ones in `stats` and the stages' CPU time
  /// in `cpu`.
  std::optional<LoopEdge> detect(const MapperEntry& query, const MapperEntries& entries,
                                 const StreamGroups& groups, MapperStats& stats,
                                 MapperCpu& cpu) const;

 private:
  using Candidate = std::pair<const MapperEntry*, Eigen::Isometry3d>;

  /// Keyframes of the same stream closer than min_travel_gap along the path are neighbours,
  /// not loops.
  bool eligible(const MapperEntry& query, const MapperEntry& candidate,
                const StreamGroups& groups) const;
  /// The eligible keyframe of the query's group nearest to its current pose estimate, and the
  /// query's pose in its frame by those estimates.
  std::optional<Candidate> proximity_candidate(const MapperEntry& query,
                                               const MapperEntries& entries,
                                               const StreamGroups& groups) const;
  /// The descriptor's best candidate for `query` and the query's pose in its frame (from the
  /// descriptor's yaw), if the descriptor distance passes the threshold.
  std::optional<Candidate> descriptor_candidate(const MapperEntry& query,
                                                const MapperEntries& entries,
                                                const StreamGroups& groups) const;
  /// Target of a verification: the candidate and its neighbours of the same stream, in the
  /// candidate's sensor frame by odometry.
  VoxelMap submap_of(const MapperEntry& candidate, const MapperEntries& entries,
                     const StreamGroups& groups) const;

  const MapperConfig& config_;
};

}  // namespace litamin2::mapping

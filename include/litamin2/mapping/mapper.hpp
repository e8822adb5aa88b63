#pragma once
/// The mapping back end shared by the aggregator and `litamin2-odometry --loop-closure`:
/// keyframe chains per stream, place recognition and LiTAMIN2 verification of loop candidates
/// within and between streams, pose-graph optimisation, and the global distribution map.
///
/// Not thread-safe: one owner calls it (the aggregator's mapping thread).

#include "litamin2/core/keyframe.hpp"
#include "litamin2/mapping/loop_edge.hpp"
#include "litamin2/mapping/mapper_config.hpp"
#include "litamin2/mapping/mapper_stats.hpp"

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace litamin2::mapping {

/// A keyframe's corrected pose.
struct KeyframePose {
  KeyframeKey key;
  /// Sensor pose in `frame`.
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  /// The stream whose odometry frame the pose is in: the first stream (in canonical order) of
  /// the group of streams joined by loops. All streams joined to the first stream of all share
  /// the map frame.
  std::string frame;
};

struct OptimizeSummary {
  /// The graph was optimised (false when nothing changed since the last call).
  bool ran = false;
  int keyframes = 0;
  int odometry_edges = 0;
  int loop_edges = 0;
  int iterations = 0;
  double initial_cost = 0.0;
  double final_cost = 0.0;
  double milliseconds = 0.0;
};

enum class AddStatus { kAdded, kDuplicate };

class Mapper {
 public:
  /// Throws ConfigError if the config is invalid.
  explicit Mapper(const MapperConfig& config);
  ~Mapper();
  Mapper(Mapper&&) noexcept;
  Mapper& operator=(Mapper&&) noexcept;

  /// Adds a keyframe of any stream, in any order; a key already present is ignored
  /// (Duplicate). Place recognition runs against the keyframes present; verified loops are
  /// added to the graph and appended to `new_loops` if given. Does not optimise.
  AddStatus add_keyframe(Keyframe keyframe, std::vector<LoopEdge>* new_loops = nullptr);
  /// Optimises the pose graph when loops were added since the last optimisation.
  OptimizeSummary optimize();

  bool contains(const KeyframeKey& key) const;
  const Keyframe* keyframe(const KeyframeKey& key) const;
  /// Corrected poses of every keyframe, ordered by key.
  std::vector<KeyframePose> poses() const;
  std::optional<KeyframePose> pose(const KeyframeKey& key) const;
  /// The correction of a stream's odometry: corrected = correction * odom_pose, from the
  /// stream's latest keyframe at or before `id` (the latest keyframe if id is absent).
  std::optional<KeyframePose> correction(const std::string& stream,
                                         std::optional<std::uint64_t> id = std::nullopt) const;
  /// The map frame: the anchor of the group holding the canonically first keyframe of all
  /// (canonical_before; every group is in the frame of its anchor stream, of two
  /// groups that meet the one whose anchor's first keyframe comes first keeps its frame).
  /// Empty without keyframes.
  std::string map_anchor() const;
  const std::vector<LoopEdge>& loops() const;
  MapperStats stats() const;
  MapperCpu cpu() const;
  const MapperConfig& config() const;

  /// Distributions of the global map in the frame of the first stream, built from every
  /// keyframe joined to it at the corrected poses, on config().map_voxel_size voxels.
  std::vector<Distribution> global_map() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace litamin2::mapping

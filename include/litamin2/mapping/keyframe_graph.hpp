#pragma once
/// What the mapper holds in memory for every keyframe (KeyframeNode: identity, odometry,
/// descriptor, current pose; about 1.7 kB) and the structures over them that the place
/// search and the optimisation need: the streams' chains and groups, the ring-key index and
/// the spatial grid of current positions. Distributions are not here: they come from the
/// DistributionCache when a verification, a submap or a map tile needs them.

#include "litamin2/core/keyframe.hpp"
#include "litamin2/mapping/place_descriptor.hpp"
#include "litamin2/mapping/ring_key_index.hpp"
#include "litamin2/mapping/spatial_grid.hpp"
#include "litamin2/mapping/stream_groups.hpp"

#include <Eigen/Geometry>
#include <cstdint>
#include <map>
#include <vector>

namespace litamin2::mapping {

struct KeyframeNode {
  KeyframeKey key;
  Stamp stamp;
  /// Voxel edge of the keyframe's distributions, metres.
  double voxel_size = 0.0;
  /// Sensor pose in the stream's odometry frame.
  Eigen::Isometry3d odom_pose = Eigen::Isometry3d::Identity();
  /// The tracker's covariance of odom_pose (Keyframe::covariance, in float: what the odometry
  /// edges need, at half the bytes).
  Eigen::Matrix<float, 6, 6> covariance = Eigen::Matrix<float, 6, 6>::Zero();
  PlaceDescriptor descriptor;
  /// Current estimate of the sensor pose in the frame of the stream's group's anchor.
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  /// Odometry path length from the stream's first present keyframe, metres.
  double path_length = 0.0;
  /// The stream's index in StreamGroups.
  std::uint32_t stream = 0;
  /// An endpoint of a loop edge that has been through an optimisation: the local
  /// optimisation's regions start at such keyframes (graph_optimizer.hpp).
  bool anchored = false;
};

class KeyframeGraph {
 public:
  /// `rings`: the descriptors' ring count; `cell_size`: the spatial grid's cell, metres.
  KeyframeGraph(int rings, double cell_size);

  /// Adds a node (its key not present yet), keeping the stream's path lengths; returns its
  /// index. The node's pose is set by the caller beforehand.
  std::uint32_t add(KeyframeNode node);
  /// Room for `nodes` nodes in all (a restore of a known size).
  void reserve(std::size_t nodes);

  /// Moves a node (updates the spatial grid and marks it changed). The rotation is
  /// re-orthonormalised (core/so3.hpp orthonormalized): the full pass and the merges correct
  /// poses by products of poses, whose rounding would otherwise grow without bound.
  void set_pose(std::uint32_t node, const Eigen::Isometry3d& pose);

  const KeyframeNode& node(std::uint32_t i) const { return nodes_[i]; }
  KeyframeNode& mutable_node(std::uint32_t i) { return nodes_[i]; }
  const std::vector<KeyframeNode>& nodes() const { return nodes_; }
  std::size_t size() const { return nodes_.size(); }
  /// The node of a key, or -1.
  std::int64_t find(const KeyframeKey& key) const;
  /// Node indices ordered by key.
  const std::map<KeyframeKey, std::uint32_t>& by_key() const { return by_key_; }

  const StreamGroups& groups() const { return groups_; }
  StreamGroups& groups() { return groups_; }
  const RingKeyIndex& ring_keys() const { return ring_keys_; }
  const SpatialGrid& grid() const { return grid_; }

  /// Nodes whose pose changed since the last call (set_pose, add), ascending; clears the set.
  std::vector<std::uint32_t> take_changed();

 private:
  void update_path_lengths(std::uint32_t stream, std::uint64_t from_id);

  std::vector<KeyframeNode> nodes_;
  std::map<KeyframeKey, std::uint32_t> by_key_;
  StreamGroups groups_;
  RingKeyIndex ring_keys_;
  SpatialGrid grid_;
  std::vector<bool> changed_;
  std::vector<std::uint32_t> changed_list_;
};

}  // namespace litamin2::mapping

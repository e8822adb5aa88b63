#pragma once
/// The mapping back end shared by the aggregator and `litamin2-odometry --loop-closure`:
/// keyframe chains per stream, place recognition and LiTAMIN2 verification of loop candidates
/// within and between streams, pose-graph optimisation, and the global distribution map.
///
/// In memory per keyframe: its KeyframeNode (keyframe_graph.hpp); the distributions are in a
/// DistributionCache (all of them by default; the aggregator's is bounded and reads its store).
/// optimize() is local to the new loops' region; optimize_full() (or full_pass_problem(),
/// solved elsewhere, then apply_full_pass()) is the full pass (graph_optimizer.hpp).
///
/// Not thread-safe: one owner calls it (the aggregator's mapping thread).

#include "litamin2/core/keyframe.hpp"
#include "litamin2/mapping/distribution_cache.hpp"
#include "litamin2/mapping/graph_optimizer.hpp"
#include "litamin2/mapping/keyframe_graph.hpp"
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
  /// Older loop ends held constant by the local optimisation (local_hold_loops).
  int held_ends = 0;
  /// Keyframes solved (free) by the local optimisation, and those of its region held fixed
  /// by local_max_free_keyframes.
  int free_keyframes = 0;
  int bounded_keyframes = 0;
  /// A bounded region could not accommodate a new loop, so it was widened and solved again.
  bool widened = false;
  double initial_cost = 0.0;
  double final_cost = 0.0;
  double milliseconds = 0.0;
};

enum class AddStatus { kAdded, kDuplicate };

class Mapper {
 public:
  /// Throws ConfigError if the config is invalid. Without a cache, every keyframe's
  /// distributions are kept in memory.
  explicit Mapper(const MapperConfig& config, std::unique_ptr<DistributionCache> cache = nullptr);
  ~Mapper();
  Mapper(Mapper&&) noexcept;
  Mapper& operator=(Mapper&&) noexcept;

  /// Adds a keyframe of any stream, in any order; a key already present is ignored
  /// (Duplicate). Place recognition runs against the keyframes present; verified loops are
  /// added to the graph and appended to `new_loops` if given. Does not optimise.
  /// `descriptor`: the keyframe's place descriptor if the caller made it already.
  AddStatus add_keyframe(Keyframe keyframe, std::vector<LoopEdge>* new_loops = nullptr,
                         const PlaceDescriptor* descriptor = nullptr);
  /// The place descriptor the mapper makes of a keyframe's distributions.
  PlaceDescriptor describe(const std::vector<Distribution>& distributions) const;
  /// Optimises the region of the loops added since the last optimisation (local).
  OptimizeSummary optimize();
  /// The local optimisation if loops are pending, then a full pass, here and now.
  OptimizeSummary optimize_full();
  /// The full pass's problem, to solve on another thread (GraphOptimizer::solve_full_pass)
  /// while the mapper goes on, then apply_full_pass().
  FullPassProblem full_pass_problem() const;
  void apply_full_pass(const FullPassProblem& problem);
  /// Loops checked since the latest full_pass_problem() (0: a full pass would change little).
  std::size_t loops_since_full_pass() const;

  /// Restores a mapper's state without registrations: nodes with their descriptors and
  /// corrected poses (in any order; keys unique) and the loop edges between them (all
  /// checked), and the loops that were waiting for a merge's confirmation (pending_merges();
  /// those whose ends are now in one group are dropped). The mapper must be empty. Throws
  /// std::invalid_argument for a loop whose keyframes are missing.
  void restore(std::vector<KeyframeNode> nodes, const std::vector<LoopEdge>& loops,
               const std::vector<LoopEdge>& pending_merges = {});

  /// The descriptors' cells (1.2 kB a keyframe, most of what a node holds) live outside the
  /// graph from now on: the nodes keep their ring keys, which the place index shortlists by,
  /// and a search reads the shortlisted keyframes' cells back through `loader` (the
  /// aggregator's store). Releases the cells of every node held now, and of each keyframe added
  /// later once its own search is done.
  void keep_descriptor_cells_outside(DescriptorLoader loader);
  /// Descriptors read back through the loader so far.
  std::size_t descriptor_loads() const;

  bool contains(const KeyframeKey& key) const;
  const KeyframeNode* node(const KeyframeKey& key) const;
  const KeyframeGraph& graph() const;
  DistributionCache& cache() const;
  /// Keyframes whose pose changed (added, optimised) since the last call, by node index.
  std::vector<std::uint32_t> take_changed();
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
  /// The verified loops between two groups waiting for their merge's confirmation
  /// (merge_confirmation.hpp), oldest first: not in the graph, but what a restart must keep.
  std::vector<LoopEdge> pending_merges() const;
  /// Counts the changes of pending_merges() (to persist it only when it changed).
  std::uint64_t pending_merges_version() const;
  MapperStats stats() const;
  MapperCpu cpu() const;
  /// The stream's odometry yaw drift estimate (yaw_drift.hpp), radians a metre; 0 for an
  /// unknown stream, before an estimate, or with PoseGraphConfig::yaw_drift_window 0.
  double yaw_drift_per_m(const std::string& stream) const;
  const MapperConfig& config() const;

  /// Distributions of the global map in the frame of the first stream, built from every
  /// keyframe joined to it at the corrected poses, on config().map_voxel_size voxels.
  std::vector<Distribution> global_map() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace litamin2::mapping

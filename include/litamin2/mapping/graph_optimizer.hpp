#pragma once
/// The mapper's two optimisations of its keyframe graph, built on pose_graph.hpp:
///
/// - local (after new loops, on the mapping thread): for each new loop, its newer keyframe's
///   stream from the latest keyframe before it that an earlier loop anchored (at most
///   local_max_keyframes back) to the stream's end is free; every other keyframe that an edge
///   ties to those is fixed. Its cost is that of the drift the loop corrects, not the map's.
///   New loops the region cannot fit within loop_consistency_sigmas are dropped (as before).
///   With local_hold_loops, an older end already held by that many checked loops near it
///   stays constant and spreads nothing (the newer end's region takes the correction).
///   With local_max_free_keyframes, the ends' neighbourhoods are trimmed to the keyframes
///   nearest the ends until that many are free (the stretches since the latest earlier loops
///   and the keyframes between two ends always are); the rest is held fixed (the full pass
///   moves it). With local_widen_for_loops, a bounded solve that cannot fit a new loop frees
///   the whole stretches holding its ends and is solved again before the loop is dropped.
/// - full pass (in the background): every stream cut into rigid segments of
///   segment_keyframes consecutive keyframes, one node each, with the odometry and checked
///   loop edges between segments; one fixed segment per group. The problem is a copy
///   (FullPassProblem) solved without the graph, then applied: each keyframe moves with its
///   segment's correction, keyframes added meanwhile with their stream's last segment's.
///
/// In both, the first keyframe of each group's anchor stream holds the group's frame (for the
/// map frame: the first vehicle's first pose) and never moves.

#include "litamin2/mapping/keyframe_graph.hpp"
#include "litamin2/mapping/loop_edge.hpp"
#include "litamin2/mapping/mapper_config.hpp"
#include "litamin2/mapping/mapper_stats.hpp"
#include "litamin2/mapping/pose_graph.hpp"
#include "litamin2/mapping/yaw_drift.hpp"

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace litamin2::mapping {

/// The loops of the graph, with their nodes, and which have been through an optimisation.
struct GraphLoops {
  std::vector<LoopEdge> edges;
  /// (from, to) nodes of each edge.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> nodes;
  /// edges[i] went through an optimisation and was consistent: it gets the robust loss.
  std::vector<bool> checked;
  /// The checked loops at each node.
  std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> at_node;

  void add(const LoopEdge& edge, std::uint32_t from, std::uint32_t to);
  /// Marks every loop checked (and its endpoints anchored).
  void check_all(KeyframeGraph& graph);
  std::size_t size() const { return edges.size(); }
};

struct LocalOptimization {
  bool ran = false;
  /// Keyframes in the problem: free (solved) and fixed.
  int keyframes = 0;
  int fixed = 0;
  int free = 0;
  /// Keyframes of the region held fixed by PoseGraphConfig::local_max_free_keyframes.
  int bounded = 0;
  /// The bounded region could not accommodate a new loop: solved again, widened
  /// (PoseGraphConfig::local_widen_for_loops).
  bool widened = false;
  int odometry_edges = 0;
  int loop_edges = 0;
  int iterations = 0;
  double initial_cost = 0.0;
  double final_cost = 0.0;
  /// New loops dropped as inconsistent.
  int dropped = 0;
  /// New loops' older ends held constant (PoseGraphConfig::local_hold_loops).
  int held_ends = 0;
};

/// A full pass, copied out of the graph so that another thread can solve it.
struct FullPassProblem {
  PoseGraphConfig config;
  /// Segment poses (solved in place) and as they were at the copy.
  std::vector<Eigen::Isometry3d> poses;
  std::vector<Eigen::Isometry3d> before;
  std::vector<bool> fixed;
  std::vector<PoseGraphEdge> edges;
  /// Each node's segment at the copy (nodes added later are not listed).
  std::vector<std::int32_t> segment_of_node;
  /// Each stream's group anchor and last segment at the copy.
  std::vector<std::uint32_t> anchor_of_stream;
  std::vector<std::int32_t> last_segment_of_stream;
  std::size_t loop_edges = 0;
  /// Keyframes a segment holds in this pass (PoseGraphConfig::segment_keyframes, or more under
  /// full_pass_max_segments).
  std::size_t segment_keyframes = 0;
  PoseGraphResult result;
  /// Wall and thread CPU time of solve_full_pass.
  double milliseconds = 0.0;
  double cpu_s = 0.0;
};

/// Keyframes per full-pass segment for a graph of `keyframes`: segment_keyframes, times the
/// smallest factor that leaves at most full_pass_max_segments segments (plus each stream's last,
/// partial one).
std::size_t full_pass_segment_keyframes(const PoseGraphConfig& config, std::size_t keyframes);

class GraphOptimizer {
 public:
  /// `config` must outlive the optimizer, and so must `drift` if given: the odometry edges
  /// then take each stream's yaw drift out (yaw_drift.hpp).
  explicit GraphOptimizer(const MapperConfig& config, const YawDriftEstimator* drift = nullptr)
      : config_(config), drift_(drift) {}

  /// The local optimisation of the unchecked loops (see the file comment); drops the
  /// inconsistent ones from `loops` and checks the others.
  LocalOptimization optimize_local(KeyframeGraph& graph, GraphLoops& loops,
                                   MapperStats& stats) const;

  /// The full pass's problem over the graph's current state.
  /// `pass`: the full pass's number, which shifts the segments' cuts
  /// (PoseGraphConfig::full_pass_shift_segments).
  FullPassProblem full_pass_problem(const KeyframeGraph& graph, const GraphLoops& loops,
                                    std::size_t pass = 0) const;
  /// Solves it (thread-safe: touches nothing else).
  static void solve_full_pass(FullPassProblem& problem);
  /// Moves the graph's keyframes by the solved segments' corrections. Streams whose group
  /// changed since the copy keep their poses (the next pass includes them), and so do
  /// keyframes the correction would move by less than `min_shift` metres and `min_turn` rad
  /// (PoseGraphConfig::full_pass_min_shift). Returns the keyframes moved.
  static std::size_t apply_full_pass(const FullPassProblem& problem, KeyframeGraph& graph,
                                     double min_shift = 0.0, double min_turn = 0.0);

  /// The odometry edge from keyframe a to the next present keyframe b of its stream, without
  /// the stream's yaw drift estimate (YawDriftEstimator); its
  /// uncertainty by distance, or from b's tracker covariance (PoseGraphConfig::
  /// odometry_covariance). b's covariance is relative to a only when b directly follows a (no
  /// keyframe missing in between); otherwise, and when b has none, by distance.
  PoseGraphEdge odometry_edge(const KeyframeNode& a, const KeyframeNode& b) const;
  /// A loop edge (robust once checked).
  static PoseGraphEdge loop_edge(const LoopEdge& loop, bool robust);
  /// The loop's residual at poses from, to is within loop_consistency_sigmas.
  bool consistent(const LoopEdge& loop, const Eigen::Isometry3d& from,
                  const Eigen::Isometry3d& to) const;
  /// The keyframe's neighbourhood (itself and local_hops keyframes either side along its
  /// stream) holds at least local_hold_loops checked loops (never with local_hold_loops 0).
  bool held_by_loops(std::uint32_t node, const KeyframeGraph& graph, const GraphLoops& loops) const;

 private:
  const MapperConfig& config_;
  const YawDriftEstimator* drift_ = nullptr;
};

}  // namespace litamin2::mapping

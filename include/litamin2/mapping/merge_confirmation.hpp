#pragma once
/// Confirmation of the loops that would join two groups of streams (two vehicles' frames).
///
/// A loop inside a group is checked by the optimisation: the graph must accommodate it within
/// loop_consistency_sigmas or it is dropped (graph_optimizer.hpp). A loop between two groups
/// cannot be checked that way: the later group is moved rigidly onto it (Mapper), so it always
/// fits. One wrong place match (a street grid has many corners that look alike turned by 90
/// degrees) then puts a whole vehicle's map in the wrong place, and every later loop between
/// the two contradicts it. So a merge waits until `merge_confirmations` verified loops between
/// the same two groups, at places at least `merge_min_separation` apart in the earlier group's
/// frame, agree on where the later group's frame lies: the pairwise consistency test of
/// inter-robot loops in LAMP 2.0 / PCM (Mangelson et al., ICRA 2018), reduced to a chain of
/// agreeing pairs with the newest loop. Agreement: the pose one pending loop predicts for the
/// newer loop's keyframe (through the two groups' current poses) is within
/// merge_agreement_m + merge_agreement_per_m * separation and merge_agreement_deg of the pose
/// the newer loop measures; the tolerance grows with the separation because the odometry
/// between the two places drifts.
///
/// Pending loops are not part of the graph; the aggregator persists them (pending(), version())
/// and a restart restores them. At most kMaxPending of them are kept, the oldest dropped
/// first; those whose two ends have come to one group by other merges are dropped.

#include "litamin2/mapping/keyframe_graph.hpp"
#include "litamin2/mapping/loop_edge.hpp"
#include "litamin2/mapping/mapper_config.hpp"

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <vector>

namespace litamin2::mapping {

/// A verified loop between node `from` (LoopEdge::from) and node `to` (LoopEdge::to).
struct MergeCandidate {
  LoopEdge edge;
  std::uint32_t from = 0;
  std::uint32_t to = 0;
};

/// How far apart two inter-group loops' places are and how much they disagree about the
/// transform between the groups (see the file comment). Both loops must join the same two
/// groups; `earlier`'s ends may be in either order.
struct MergeDisagreement {
  /// Distance between the two loops' ends in the group of `later.from`, metres.
  double separation = 0.0;
  /// Position and rotation difference at later.to between the pose `earlier` predicts and
  /// the pose `later` measures, metres and degrees.
  double translation = 0.0;
  double rotation_deg = 0.0;
};
MergeDisagreement merge_disagreement(const MergeCandidate& earlier, const MergeCandidate& later,
                                     const KeyframeGraph& graph);

class MergeConfirmation {
 public:
  static constexpr std::size_t kMaxPending = 4096;

  explicit MergeConfirmation(const PlaceRecognitionConfig& config) : config_(config) {}

  /// Offers a verified loop whose two ends are in different groups. Returns the loops that
  /// confirm the merge, the earlier pending ones first and `candidate` last (they are removed
  /// from the pending ones), or nothing when `candidate` is kept pending.
  std::vector<MergeCandidate> offer(const MergeCandidate& candidate, const KeyframeGraph& graph);

  std::size_t pending() const { return pending_.size(); }
  /// The pending loops, oldest first.
  const std::deque<MergeCandidate>& pending_loops() const { return pending_; }
  /// Counts the changes of the pending loops.
  std::uint64_t version() const { return version_; }
  /// Replaces the pending loops (a restart), oldest first; those whose ends are in one group
  /// are dropped and the oldest beyond kMaxPending too.
  void restore(const std::vector<MergeCandidate>& pending, const KeyframeGraph& graph);

 private:
  bool agrees(const MergeDisagreement& d) const;

  PlaceRecognitionConfig config_;
  std::deque<MergeCandidate> pending_;
  std::uint64_t version_ = 0;
};

}  // namespace litamin2::mapping

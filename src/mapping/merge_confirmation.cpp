#include "litamin2/mapping/merge_confirmation.hpp"

#include <cmath>

namespace litamin2::mapping {

MergeDisagreement merge_disagreement(const MergeCandidate& earlier, const MergeCandidate& later,
                                     const KeyframeGraph& graph) {
  const StreamGroups& groups = graph.groups();
  const std::uint32_t group_a = groups.anchor_of(graph.node(later.from).stream);
  // The earlier loop as (its end in later.from's group a, its end in the other group b, the
  // pose of b's end in a's end's frame).
  const bool same_order = groups.anchor_of(graph.node(earlier.from).stream) == group_a;
  const std::uint32_t a = same_order ? earlier.from : earlier.to;
  const std::uint32_t b = same_order ? earlier.to : earlier.from;
  const Eigen::Isometry3d relative =
      same_order ? earlier.edge.relative : earlier.edge.relative.inverse();
  // Group b's frame in group a's according to the earlier loop, then the newer loop's
  // keyframe through it and through the newer loop itself.
  const Eigen::Isometry3d b_in_a = graph.node(a).pose * relative * graph.node(b).pose.inverse();
  const Eigen::Isometry3d predicted = b_in_a * graph.node(later.to).pose;
  const Eigen::Isometry3d measured = graph.node(later.from).pose * later.edge.relative;
  const Eigen::Isometry3d error = predicted.inverse() * measured;
  MergeDisagreement d;
  d.separation =
      (graph.node(a).pose.translation() - graph.node(later.from).pose.translation()).norm();
  d.translation = error.translation().norm();
  d.rotation_deg = Eigen::AngleAxisd(error.rotation()).angle() * 180.0 / M_PI;
  return d;
}

bool MergeConfirmation::agrees(const MergeDisagreement& d) const {
  return d.separation >= config_.merge_min_separation &&
         d.translation <=
             config_.merge_agreement_m + config_.merge_agreement_per_m * d.separation &&
         d.rotation_deg <= config_.merge_agreement_deg;
}

std::vector<MergeCandidate> MergeConfirmation::offer(const MergeCandidate& candidate,
                                                     const KeyframeGraph& graph) {
  if (config_.merge_confirmations <= 1) return {candidate};
  const StreamGroups& groups = graph.groups();
  const std::uint32_t ga = groups.anchor_of(graph.node(candidate.from).stream);
  const std::uint32_t gb = groups.anchor_of(graph.node(candidate.to).stream);
  std::vector<std::size_t> agreeing;
  for (std::size_t i = 0; i < pending_.size();) {
    const MergeCandidate& p = pending_[i];
    const std::uint32_t pa = groups.anchor_of(graph.node(p.from).stream);
    const std::uint32_t pb = groups.anchor_of(graph.node(p.to).stream);
    if (pa == pb) {  // joined by other loops since: it has nothing left to confirm
      pending_.erase(pending_.begin() + static_cast<std::ptrdiff_t>(i));
      ++version_;
      continue;
    }
    if (((pa == ga && pb == gb) || (pa == gb && pb == ga)) &&
        agrees(merge_disagreement(p, candidate, graph)))
      agreeing.push_back(i);
    ++i;
  }
  if (agreeing.size() + 1 < static_cast<std::size_t>(config_.merge_confirmations)) {
    pending_.push_back(candidate);
    if (pending_.size() > kMaxPending) pending_.pop_front();
    ++version_;
    return {};
  }
  std::vector<MergeCandidate> out;
  for (std::size_t i : agreeing) out.push_back(pending_[i]);
  for (auto it = agreeing.rbegin(); it != agreeing.rend(); ++it)
    pending_.erase(pending_.begin() + static_cast<std::ptrdiff_t>(*it));
  if (!agreeing.empty()) ++version_;
  out.push_back(candidate);
  return out;
}

void MergeConfirmation::restore(const std::vector<MergeCandidate>& pending,
                                const KeyframeGraph& graph) {
  const StreamGroups& groups = graph.groups();
  pending_.clear();
  for (const MergeCandidate& c : pending) {
    if (groups.anchor_of(graph.node(c.from).stream) == groups.anchor_of(graph.node(c.to).stream))
      continue;
    pending_.push_back(c);
    if (pending_.size() > kMaxPending) pending_.pop_front();
  }
  ++version_;
}

}  // namespace litamin2::mapping

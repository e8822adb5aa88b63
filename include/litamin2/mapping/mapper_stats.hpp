#pragma once
/// What the mapper counts and how long its stages take.

#include <cstddef>

namespace litamin2::mapping {

struct MapperStats {
  std::size_t keyframes = 0;
  std::size_t streams = 0;
  std::size_t duplicates = 0;
  std::size_t candidates = 0;
  /// Proximity candidates verified, and of them accepted; proximity candidates not verified
  /// because their descriptor was too far (proximity_max_descriptor_distance).
  std::size_t proximity_candidates = 0;
  std::size_t proximity_verified = 0;
  std::size_t proximity_skipped = 0;
  /// Proximity candidates of a stream not looped with recently, a nearer keyframe of a recent
  /// partner passed over (proximity_partner_gap).
  std::size_t proximity_new_partner = 0;
  /// Descriptor searches run: only for keyframes whose proximity candidate was missing,
  /// skipped or rejected (loop_detector.hpp).
  std::size_t descriptor_searches = 0;
  /// Place searches limited to other groups because the verification allowance was spent
  /// (verification_budget_per_keyframe).
  std::size_t searches_over_budget = 0;
  std::size_t verified = 0;
  /// Candidates rejected by verification or, after optimisation, as inconsistent.
  std::size_t rejected = 0;
  /// Of those, verified loops the graph could not accommodate.
  std::size_t inconsistent = 0;
  /// Verified loops between two groups kept waiting for a confirmation
  /// (merge_confirmation.hpp), and merges confirmed (groups joined).
  std::size_t merges_pending = 0;
  std::size_t merges = 0;
  std::size_t optimizations = 0;
  /// Full passes applied (Mapper::apply_full_pass).
  std::size_t full_passes = 0;
  /// Keyframes the full passes moved (the others moved less than full_pass_min_shift).
  std::size_t full_pass_keyframes_moved = 0;
  /// Local optimisations and full passes whose solution ran off (pose_graph.hpp,
  /// within_reach): refused.
  std::size_t diverged = 0;
  /// Odometry yaw drift estimates taken, and rejected as beyond
  /// PoseGraphConfig::yaw_drift_max_deg_per_100m (yaw_drift.hpp).
  std::size_t yaw_drift_estimates = 0;
  std::size_t yaw_drift_rejected = 0;
};

/// CPU time (of the calling thread) spent in the mapper's stages since construction, seconds.
struct MapperCpu {
  /// Place descriptors of new keyframes.
  double descriptor_s = 0.0;
  /// Insertion into the keyframe chain: initial pose, path lengths.
  double chain_s = 0.0;
  /// Proximity candidate search (nearest keyframe by pose estimate).
  double proximity_s = 0.0;
  /// Descriptor candidate search (ring-key shortlist and full descriptor distances).
  double descriptor_search_s = 0.0;
  /// Loop verification (candidate submap and registration).
  double verification_s = 0.0;
  /// Pose-graph optimisation (local).
  double optimize_s = 0.0;
  /// Full passes run by optimize_full() on the calling thread.
  double full_pass_s = 0.0;
};

}  // namespace litamin2::mapping

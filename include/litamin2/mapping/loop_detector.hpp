#pragma once
/// Place recognition for a new keyframe: candidates from its group's nearest keyframe by pose
/// estimate (the spatial grid) and from the place descriptors (the ring-key index's shortlist,
/// then the full descriptor distance), each verified by LiTAMIN2 registration to a submap of
/// the candidate and its neighbours (loop_verifier.hpp); the first verified one is the loop.
/// The descriptors are searched only when the proximity candidate is missing or rejected.
/// PlaceRecognitionConfig::search = kLinear scans every keyframe instead of the indexes, with
/// the same candidates while no grid cell holds more than proximity_cell_keyframes (for
/// comparisons and tests).

#include "litamin2/core/voxel_map.hpp"
#include "litamin2/mapping/distribution_cache.hpp"
#include "litamin2/mapping/keyframe_graph.hpp"
#include "litamin2/mapping/loop_edge.hpp"
#include "litamin2/mapping/mapper_config.hpp"
#include "litamin2/mapping/mapper_stats.hpp"

#include <Eigen/Geometry>
#include <optional>
#include <utility>

namespace litamin2::mapping {

/// A loop candidate: the keyframe, and the query's pose in its frame to start verifying from.
struct LoopCandidate {
  std::uint32_t node = 0;
  Eigen::Isometry3d initial = Eigen::Isometry3d::Identity();
};

/// Which keyframes a place search considers.
enum class SearchScope {
  /// Every eligible keyframe: the proximity candidate of the query's group and the
  /// descriptor's candidate of any group.
  kAll,
  /// Only other groups' keyframes (the descriptor's candidate; the proximity candidate is of
  /// the query's group by definition): PlaceRecognitionConfig::loop_spacing after a loop.
  kOtherGroups,
};

class LoopDetector {
 public:
  /// `config` must outlive the detector.
  explicit LoopDetector(const MapperConfig& config) : config_(config) {}

  /// Nodes whose descriptor has no cells are compared through `loader` (empty: none may lack
  /// them).
  void set_descriptor_loader(DescriptorLoader loader) { loader_ = std::move(loader); }
  /// Descriptors read back through the loader so far.
  std::size_t descriptor_loads() const { return descriptor_loads_; }

  /// The loop of node `query` (with its distributions) with the keyframes present, if a
  /// candidate is verified; counts candidates, verified and rejected ones in `stats` and the
  /// stages' CPU time in `cpu`. `recent_partners` (sorted): the streams the query's stream
  /// closed a loop with in the last proximity_partner_gap metres of its path.
  std::optional<LoopEdge> detect(std::uint32_t query,
                                 const std::vector<Distribution>& distributions,
                                 const KeyframeGraph& graph, DistributionCache& cache,
                                 MapperStats& stats, MapperCpu& cpu,
                                 SearchScope scope = SearchScope::kAll,
                                 const std::vector<std::uint32_t>& recent_partners = {}) const;

  /// The eligible keyframe of the query's group nearest to its current pose estimate among
  /// the streams not in `recent_partners` (sorted), if any is within proximity_radius, else
  /// among all; `new_partner` (if given) tells whether a nearer one of a partner was passed over.
  std::optional<LoopCandidate> proximity_candidate(
      std::uint32_t query, const KeyframeGraph& graph,
      const std::vector<std::uint32_t>& recent_partners = {}, bool* new_partner = nullptr) const;
  /// The descriptor's best candidate, if its distance passes the threshold.
  std::optional<LoopCandidate> descriptor_candidate(std::uint32_t query, const KeyframeGraph& graph,
                                                    SearchScope scope = SearchScope::kAll) const;

 private:
  /// Keyframes of the same stream closer than min_travel_gap along the path are neighbours,
  /// not loops.
  bool eligible(const KeyframeNode& query, std::uint32_t candidate, const KeyframeGraph& graph,
                SearchScope scope = SearchScope::kAll) const;
  /// Target of a verification: the candidate and its neighbours of the same stream, in the
  /// candidate's sensor frame by odometry.
  VoxelMap submap_of(std::uint32_t candidate, const KeyframeGraph& graph,
                     DistributionCache& cache) const;
  /// The node's descriptor with its cells: the node's own, or read back into `loaded`.
  const PlaceDescriptor& with_cells(const KeyframeNode& node, PlaceDescriptor& loaded) const;

  const MapperConfig& config_;
  DescriptorLoader loader_;
  mutable std::size_t descriptor_loads_ = 0;
};

}  // namespace litamin2::mapping

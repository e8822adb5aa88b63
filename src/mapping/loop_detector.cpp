#include "litamin2/mapping/loop_detector.hpp"

#include "litamin2/core/stopwatch.hpp"
#include "litamin2/mapping/distribution_moments.hpp"
#include "litamin2/mapping/loop_verifier.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace litamin2::mapping {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

}  // namespace

const PlaceDescriptor& LoopDetector::with_cells(const KeyframeNode& node,
                                                PlaceDescriptor& loaded) const {
  if (!node.descriptor.cells.empty() || !loader_) return node.descriptor;
  loaded = loader_(node.key);
  ++descriptor_loads_;
  return loaded;
}

std::optional<LoopEdge> LoopDetector::detect(
    std::uint32_t query, const std::vector<Distribution>& distributions, const KeyframeGraph& graph,
    DistributionCache& cache, MapperStats& stats, MapperCpu& cpu, SearchScope scope,
    const std::vector<std::uint32_t>& recent_partners) const {
  double t = thread_cpu_seconds();
  auto lap = [&t](double& stage) {
    const double now = thread_cpu_seconds();
    stage += now - t;
    t = now;
  };
  // The candidate's verification: the loop edge if the registration accepts it.
  auto verify = [&](const LoopCandidate& candidate, bool proximity) -> std::optional<LoopEdge> {
    ++stats.candidates;
    if (proximity) ++stats.proximity_candidates;
    const VoxelMap submap = submap_of(candidate.node, graph, cache);
    const LoopVerification v = verify_loop(distributions, submap, candidate.initial,
                                           config_.verification, M_PI / config_.place.sectors);
    lap(cpu.verification_s);
    if (!v.accepted) {
      ++stats.rejected;
      return std::nullopt;
    }
    ++stats.verified;
    if (proximity) ++stats.proximity_verified;
    LoopEdge edge;
    edge.from = graph.node(candidate.node).key;
    edge.to = graph.node(query).key;
    edge.relative = v.relative;
    edge.fitness = v.fitness;
    edge.rmse = v.rmse;
    const double sr = config_.verification.rotation_sigma_deg * kDegToRad;
    const double st = config_.verification.translation_sigma;
    Vector6d info;
    info << 1.0 / (sr * sr), 1.0 / (sr * sr), 1.0 / (sr * sr), 1.0 / (st * st), 1.0 / (st * st),
        1.0 / (st * st);
    edge.information = info.asDiagonal();
    return edge;
  };
  // The nearest keyframe by pose estimate first. Only when it is missing or rejected is the
  // descriptor searched: in a fleet that has driven its streets before, most keyframes are
  // closed by proximity, and a descriptor search (the ring-key index, whose cost grows with
  // the map, and descriptors read back from the store) would find a candidate never verified.
  const double max_distance = config_.place.proximity_max_descriptor_distance;
  if (scope == SearchScope::kAll) {
    bool new_partner = false;
    const auto c = proximity_candidate(query, graph, recent_partners, &new_partner);
    if (new_partner) ++stats.proximity_new_partner;
    bool skipped = false;
    if (c && max_distance > 0.0) {
      PlaceDescriptor loaded_query, loaded_candidate;
      skipped = match_descriptors(with_cells(graph.node(query), loaded_query),
                                  with_cells(graph.node(c->node), loaded_candidate))
                    .distance > max_distance;
      if (skipped) ++stats.proximity_skipped;
    }
    lap(cpu.proximity_s);
    if (c && !skipped) {
      if (auto edge = verify(*c, true)) return edge;
    }
  }
  // The descriptor's candidate may be the same keyframe: its yaw is still another start.
  ++stats.descriptor_searches;
  const auto c = descriptor_candidate(query, graph, scope);
  lap(cpu.descriptor_search_s);
  if (c) return verify(*c, false);
  return std::nullopt;
}

bool LoopDetector::eligible(const KeyframeNode& query, std::uint32_t candidate,
                            const KeyframeGraph& graph, SearchScope scope) const {
  const KeyframeNode& c = graph.node(candidate);
  if (&c == &query) return false;
  if (scope == SearchScope::kOtherGroups)
    return graph.groups().anchor_of(c.stream) != graph.groups().anchor_of(query.stream);
  if (c.stream != query.stream) return true;
  return std::abs(query.path_length - c.path_length) >= config_.place.min_travel_gap;
}

std::optional<LoopCandidate> LoopDetector::proximity_candidate(
    std::uint32_t query, const KeyframeGraph& graph,
    const std::vector<std::uint32_t>& recent_partners, bool* new_partner) const {
  const double radius = config_.place.proximity_radius;
  if (radius <= 0.0) return std::nullopt;
  const KeyframeNode& q = graph.node(query);
  const StreamGroups& groups = graph.groups();
  const std::uint32_t group = groups.anchor_of(q.stream);
  // The nearest of all, and the nearest of the streams not looped with recently.
  struct Nearest {
    std::int64_t node = -1;
    double d_sq = 0.0;
  };
  Nearest any{-1, radius * radius}, fresh{-1, radius * radius};
  // Strictly nearer wins; at equal distance the first by key, as the linear scan (streams by
  // name, then ids) finds it.
  auto offer = [&](Nearest& best, std::uint32_t n, double d_sq) {
    if (d_sq < best.d_sq ||
        (best.node >= 0 && d_sq == best.d_sq &&
         graph.node(n).key < graph.node(static_cast<std::uint32_t>(best.node)).key)) {
      best.d_sq = d_sq;
      best.node = n;
    }
  };
  auto consider = [&](std::uint32_t n) {
    const KeyframeNode& entry = graph.node(n);
    if (groups.anchor_of(entry.stream) != group || !eligible(q, n, graph)) return;
    const double d_sq = (entry.pose.translation() - q.pose.translation()).squaredNorm();
    offer(any, n, d_sq);
    if (!std::binary_search(recent_partners.begin(), recent_partners.end(), entry.stream))
      offer(fresh, n, d_sq);
  };
  if (config_.place.search == PlaceSearch::kLinear) {
    for (const auto& [name, s] : groups.by_name()) {
      if (groups.anchor_of(s) != group) continue;
      for (const auto& [id, n] : groups.at(s).nodes) consider(n);
    }
  } else {
    graph.grid().visit_nearest_first(
        q.pose.translation(), radius,
        static_cast<std::size_t>(config_.place.proximity_cell_keyframes), consider,
        // Nothing nearer than the nearest of a new partner can change the answer.
        [&fresh] { return fresh.d_sq; });
  }
  const std::int64_t best = fresh.node >= 0 ? fresh.node : any.node;
  if (best < 0) return std::nullopt;
  if (new_partner) *new_partner = fresh.node >= 0 && fresh.node != any.node;
  const KeyframeNode& b = graph.node(static_cast<std::uint32_t>(best));
  return LoopCandidate{static_cast<std::uint32_t>(best), b.pose.inverse() * q.pose};
}

std::optional<LoopCandidate> LoopDetector::descriptor_candidate(std::uint32_t query,
                                                                const KeyframeGraph& graph,
                                                                SearchScope scope) const {
  const PlaceRecognitionConfig& pc = config_.place;
  const KeyframeNode& q = graph.node(query);
  auto before = [&](std::uint32_t a, std::uint32_t b) {
    return graph.node(a).key < graph.node(b).key;
  };
  std::vector<std::uint32_t> shortlist;
  if (pc.search == PlaceSearch::kLinear) {
    std::vector<std::pair<double, std::uint32_t>> all;
    for (const auto& [key, n] : graph.by_key()) {
      if (!eligible(q, n, graph, scope)) continue;
      all.emplace_back(ring_key_distance(q.descriptor, graph.node(n).descriptor), n);
    }
    const std::size_t keep = std::min<std::size_t>(pc.ring_key_candidates, all.size());
    std::partial_sort(
        all.begin(), all.begin() + keep, all.end(), [&](const auto& a, const auto& b) {
          return a.first < b.first || (a.first == b.first && before(a.second, b.second));
        });
    for (std::size_t i = 0; i < keep; ++i) shortlist.push_back(all[i].second);
  } else {
    shortlist = graph.ring_keys().nearest(
        q.descriptor.ring_key, static_cast<std::size_t>(pc.ring_key_candidates),
        [&](std::uint32_t n) { return eligible(q, n, graph, scope); }, before);
  }
  std::int64_t best = -1;
  DescriptorMatch best_match;
  PlaceDescriptor loaded_query, loaded_candidate;
  const PlaceDescriptor& query_descriptor = with_cells(q, loaded_query);
  for (std::uint32_t n : shortlist) {
    const DescriptorMatch match =
        match_descriptors(query_descriptor, with_cells(graph.node(n), loaded_candidate));
    if (match.distance < best_match.distance) {
      best_match = match;
      best = n;
    }
  }
  if (best < 0 || best_match.distance > pc.max_descriptor_distance) return std::nullopt;
  return LoopCandidate{static_cast<std::uint32_t>(best), yaw_pose(best_match.yaw)};
}

VoxelMap LoopDetector::submap_of(std::uint32_t candidate, const KeyframeGraph& graph,
                                 DistributionCache& cache) const {
  const KeyframeNode& c = graph.node(candidate);
  VoxelizerConfig voxels;
  voxels.voxel_size = c.voxel_size > 0.0 ? c.voxel_size : 3.0;
  voxels.min_points = 1;
  VoxelMap map(voxels, VoxelMapConfig{});
  const auto& chain = graph.groups().at(c.stream).nodes;
  auto it = chain.find(c.key.id);
  auto first = it, last = it;
  for (int i = 0; i < config_.verification.submap_neighbours && first != chain.begin(); ++i)
    --first;
  for (int i = 0; i < config_.verification.submap_neighbours && std::next(last) != chain.end(); ++i)
    ++last;
  const Eigen::Isometry3d to_candidate = c.odom_pose.inverse();
  for (auto k = first;; ++k) {
    const KeyframeNode& n = graph.node(k->second);
    const Distributions d = cache.get(n.key);
    map.insert(moments_of(*d), to_candidate * n.odom_pose);
    if (k == last) break;
  }
  return map;
}

}  // namespace litamin2::mapping

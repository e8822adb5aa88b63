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

std::optional<LoopEdge> LoopDetector::detect(const MapperEntry& query, const MapperEntries& entries,
                                             const StreamGroups& groups, MapperStats& stats,
                                             MapperCpu& cpu) const {
  // The nearest keyframe by pose estimate first, then the descriptor's candidate.
  std::vector<Candidate> candidates;
  double t = thread_cpu_seconds();
  if (auto c = proximity_candidate(query, entries, groups)) candidates.push_back(*c);
  double now = thread_cpu_seconds();
  cpu.proximity_s += now - t;
  t = now;
  // The descriptor's candidate may be the same keyframe: its yaw is still another start.
  if (auto c = descriptor_candidate(query, entries, groups)) candidates.push_back(*c);
  now = thread_cpu_seconds();
  cpu.descriptor_search_s += now - t;
  t = now;
  for (const auto& [candidate, initial] : candidates) {
    ++stats.candidates;
    const VoxelMap submap = submap_of(*candidate, entries, groups);
    const LoopVerification v = verify_loop(query.keyframe.distributions, submap, initial,
                                           config_.verification, M_PI / config_.place.sectors);
    now = thread_cpu_seconds();
    cpu.verification_s += now - t;
    t = now;
    if (!v.accepted) {
      ++stats.rejected;
      continue;
    }
    ++stats.verified;
    LoopEdge edge;
    edge.from = candidate->keyframe.key;
    edge.to = query.keyframe.key;
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
  }
  return std::nullopt;
}

bool LoopDetector::eligible(const MapperEntry& query, const MapperEntry& candidate,
                            const StreamGroups& groups) const {
  if (candidate.keyframe.key.stream != query.keyframe.key.stream) return true;
  const StreamGroups::Stream& stream = groups.at(query.keyframe.key.stream);
  const double gap = std::abs(stream.path_length.at(query.keyframe.key.id) -
                              stream.path_length.at(candidate.keyframe.key.id));
  return gap >= config_.place.min_travel_gap;
}

std::optional<LoopDetector::Candidate> LoopDetector::proximity_candidate(
    const MapperEntry& query, const MapperEntries& entries, const StreamGroups& groups) const {
  const double radius = config_.place.proximity_radius;
  if (radius <= 0.0) return std::nullopt;
  const std::string group = groups.anchor_of(query.keyframe.key.stream);
  const MapperEntry* best = nullptr;
  double best_sq = radius * radius;
  // The group's streams' entries, in key order (streams by name, then ids).
  for (const auto& [name, stream] : groups.streams()) {
    if (groups.anchor_of(name) != group) continue;
    for (auto it = entries.lower_bound(KeyframeKey{name, 0});
         it != entries.end() && it->first.stream == name; ++it) {
      const MapperEntry& entry = it->second;
      if (&entry == &query || !eligible(query, entry, groups)) continue;
      const double d_sq = (entry.pose.translation() - query.pose.translation()).squaredNorm();
      if (d_sq < best_sq) {
        best_sq = d_sq;
        best = &entry;
      }
    }
  }
  if (!best) return std::nullopt;
  return std::make_pair(best, best->pose.inverse() * query.pose);
}

std::optional<LoopDetector::Candidate> LoopDetector::descriptor_candidate(
    const MapperEntry& query, const MapperEntries& entries, const StreamGroups& groups) const {
  const PlaceRecognitionConfig& pc = config_.place;
  std::vector<std::pair<double, const MapperEntry*>> shortlist;
  for (const auto& [key, entry] : entries) {
    if (&entry == &query || !eligible(query, entry, groups)) continue;
    shortlist.emplace_back(ring_key_distance(query.descriptor, entry.descriptor), &entry);
  }
  const std::size_t keep = std::min<std::size_t>(pc.ring_key_candidates, shortlist.size());
  std::partial_sort(shortlist.begin(), shortlist.begin() + keep, shortlist.end(),
                    [](const auto& a, const auto& b) {
                      return a.first < b.first || (a.first == b.first &&
                                                   a.second->keyframe.key < b.second->keyframe.key);
                    });
  const MapperEntry* best = nullptr;
  DescriptorMatch best_match;
  for (std::size_t i = 0; i < keep; ++i) {
    const DescriptorMatch match =
        match_descriptors(query.descriptor, shortlist[i].second->descriptor);
    if (match.distance < best_match.distance) {
      best_match = match;
      best = shortlist[i].second;
    }
  }
  if (!best || best_match.distance > pc.max_descriptor_distance) return std::nullopt;
  return std::make_pair(best, yaw_pose(best_match.yaw));
}

VoxelMap LoopDetector::submap_of(const MapperEntry& candidate, const MapperEntries& entries,
                                 const StreamGroups& groups) const {
  VoxelizerConfig voxels;
  voxels.voxel_size = candidate.keyframe.voxel_size > 0.0 ? candidate.keyframe.voxel_size : 3.0;
  voxels.min_points = 1;
  VoxelMap map(voxels, VoxelMapConfig{});
  const StreamGroups::Stream& stream = groups.at(candidate.keyframe.key.stream);
  auto it = stream.path_length.find(candidate.keyframe.key.id);
  auto first = it, last = it;
  for (int i = 0; i < config_.verification.submap_neighbours && first != stream.path_length.begin();
       ++i)
    --first;
  for (int i = 0;
       i < config_.verification.submap_neighbours && std::next(last) != stream.path_length.end();
       ++i)
    ++last;
  const Eigen::Isometry3d to_candidate = candidate.keyframe.odom_pose.inverse();
  for (auto k = first;; ++k) {
    const Keyframe& kf = entries.at({candidate.keyframe.key.stream, k->first}).keyframe;
    map.insert(moments_of(kf.distributions), to_candidate * kf.odom_pose);
    if (k == last) break;
  }
  return map;
}

}  // namespace litamin2::mapping

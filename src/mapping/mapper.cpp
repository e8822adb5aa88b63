#include "litamin2/mapping/mapper.hpp"

#include "litamin2/core/stopwatch.hpp"
#include "litamin2/core/voxel_map.hpp"
#include "litamin2/mapping/distribution_moments.hpp"
#include "litamin2/mapping/loop_verifier.hpp"
#include "litamin2/mapping/odometry_covariance.hpp"
#include "litamin2/mapping/place_descriptor.hpp"
#include "litamin2/mapping/pose_graph.hpp"

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>
#include <tuple>

namespace litamin2::mapping {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

}  // namespace

struct Mapper::Impl {
  struct Entry {
    Keyframe keyframe;
    PlaceDescriptor descriptor;
    /// Current estimate of the sensor pose in the frame of the stream's group's anchor.
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  };
  struct Stream {
    /// The stream's canonically first keyframe (canonical_before: stamp, then
    /// stream, then id). Of two groups that meet, the one whose anchor's first keyframe comes
    /// first keeps its frame; so a group's anchor, and the map's (the stream of the first
    /// keyframe of all), do not depend on the order in which keyframes arrived, and a mapper
    /// rebuilt from the store in canonical order agrees with the live one.
    std::int64_t first_stamp_ns = 0;
    std::uint64_t first_id = 0;
    /// Union-find parent (a stream name); the root is the group's anchor.
    std::string parent;
    /// Keyframe ids present, with the odometry path length from the stream's first keyframe.
    std::map<std::uint64_t, double> path_length;
  };

  explicit Impl(const MapperConfig& c) : config(c) { validate(config); }

  MapperConfig config;
  std::map<KeyframeKey, Entry> entries;
  std::map<std::string, Stream> streams;
  std::vector<LoopEdge> loops;
  /// loops[i] went through one optimisation and was consistent: it gets the robust loss.
  std::vector<bool> loop_checked;
  MapperStats stats;
  MapperCpu cpu;
  int loops_since_optimize = 0;

  /// True when stream a's first keyframe comes before stream b's (canonical order).
  bool starts_before(const std::string& a, const std::string& b) const {
    const Stream& sa = streams.at(a);
    const Stream& sb = streams.at(b);
    return std::tie(sa.first_stamp_ns, a, sa.first_id) <
           std::tie(sb.first_stamp_ns, b, sb.first_id);
  }

  /// The stream whose first keyframe is the first of all (empty without keyframes).
  std::string first_stream() const {
    std::string first;
    for (const auto& [name, stream] : streams)
      if (first.empty() || starts_before(name, first)) first = name;
    return first;
  }

  std::string anchor_of(const std::string& stream) const {
    std::string s = stream;
    while (streams.at(s).parent != s) s = streams.at(s).parent;
    return s;
  }

  void update_path_lengths(Stream& stream, const std::string& name) {
    double length = 0.0;
    const Keyframe* previous = nullptr;
    for (auto& [id, path] : stream.path_length) {
      const Keyframe& kf = entries.at(KeyframeKey{name, id}).keyframe;
      if (previous)
        length += (kf.odom_pose.translation() - previous->odom_pose.translation()).norm();
      path = length;
      previous = &kf;
    }
  }

  /// Initial pose of a new keyframe: chained by odometry from its nearest present neighbour
  /// in the same stream, else its odometry pose.
  Eigen::Isometry3d initial_pose(const Keyframe& kf) const {
    const Stream& stream = streams.at(kf.key.stream);
    auto next = stream.path_length.upper_bound(kf.key.id);
    const Entry* neighbour = nullptr;
    if (next != stream.path_length.begin()) {
      auto previous = std::prev(next);
      if (previous->first == kf.key.id && previous != stream.path_length.begin()) --previous;
      if (previous->first != kf.key.id) neighbour = &entries.at({kf.key.stream, previous->first});
    }
    if (!neighbour && next != stream.path_length.end())
      neighbour = &entries.at({kf.key.stream, next->first});
    if (!neighbour) return kf.odom_pose;
    return neighbour->pose * neighbour->keyframe.odom_pose.inverse() * kf.odom_pose;
  }

  /// Target of a loop verification: the candidate and its neighbours of the same stream, in
  /// the candidate's sensor frame by odometry.
  VoxelMap submap_of(const Entry& candidate) const {
    VoxelizerConfig voxels;
    voxels.voxel_size = candidate.keyframe.voxel_size > 0.0 ? candidate.keyframe.voxel_size : 3.0;
    voxels.min_points = 1;
    VoxelMap map(voxels, VoxelMapConfig{});
    const Stream& stream = streams.at(candidate.keyframe.key.stream);
    auto it = stream.path_length.find(candidate.keyframe.key.id);
    auto first = it, last = it;
    for (int i = 0;
         i < config.verification.submap_neighbours && first != stream.path_length.begin(); ++i)
      --first;
    for (int i = 0;
         i < config.verification.submap_neighbours && std::next(last) != stream.path_length.end();
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

  bool eligible(const Entry& query, const Entry& candidate) const {
    if (candidate.keyframe.key.stream != query.keyframe.key.stream) return true;
    const Stream& stream = streams.at(query.keyframe.key.stream);
    const double gap = std::abs(stream.path_length.at(query.keyframe.key.id) -
                                stream.path_length.at(candidate.keyframe.key.id));
    return gap >= config.place.min_travel_gap;
  }

  /// The descriptor's best candidate for `query` and the query's pose in its frame (from the
  /// descriptor's yaw), if the descriptor distance passes the threshold.
  std::optional<std::pair<const Entry*, Eigen::Isometry3d>> descriptor_candidate(
      const Entry& query) const {
    const PlaceRecognitionConfig& pc = config.place;
    std::vector<std::pair<double, const Entry*>> shortlist;
    for (const auto& [key, entry] : entries) {
      if (&entry == &query || !eligible(query, entry)) continue;
      shortlist.emplace_back(ring_key_distance(query.descriptor, entry.descriptor), &entry);
    }
    const std::size_t keep = std::min<std::size_t>(pc.ring_key_candidates, shortlist.size());
    std::partial_sort(
        shortlist.begin(), shortlist.begin() + keep, shortlist.end(),
        [](const auto& a, const auto& b) {
          return a.first < b.first ||
                 (a.first == b.first && a.second->keyframe.key < b.second->keyframe.key);
        });
    const Entry* best = nullptr;
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

  /// The eligible keyframe of the query's group nearest to its current pose estimate, and the
  /// query's pose in its frame by those estimates.
  std::optional<std::pair<const Entry*, Eigen::Isometry3d>> proximity_candidate(
      const Entry& query) const {
    const double radius = config.place.proximity_radius;
    if (radius <= 0.0) return std::nullopt;
    const std::string group = anchor_of(query.keyframe.key.stream);
    const Entry* best = nullptr;
    double best_sq = radius * radius;
    // The group's streams' entries, in key order (streams by name, then ids).
    for (const auto& [name, stream] : streams) {
      if (anchor_of(name) != group) continue;
      for (auto it = entries.lower_bound(KeyframeKey{name, 0});
           it != entries.end() && it->first.stream == name; ++it) {
        const Entry& entry = it->second;
        if (&entry == &query || !eligible(query, entry)) continue;
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

  /// Place recognition and verification for a newly added keyframe: the nearest keyframe by
  /// pose estimate first, then the descriptor's candidate; the first verified one is a loop.
  void detect_loops(const Entry& query, std::vector<LoopEdge>* new_loops) {
    std::vector<std::pair<const Entry*, Eigen::Isometry3d>> candidates;
    double t = thread_cpu_seconds();
    if (auto c = proximity_candidate(query)) candidates.push_back(*c);
    double now = thread_cpu_seconds();
    cpu.proximity_s += now - t;
    t = now;
    // The descriptor's candidate may be the same keyframe: its yaw is still another start.
    if (auto c = descriptor_candidate(query)) candidates.push_back(*c);
    now = thread_cpu_seconds();
    cpu.descriptor_search_s += now - t;
    t = now;
    for (const auto& [candidate, initial] : candidates) {
      ++stats.candidates;
      const VoxelMap submap = submap_of(*candidate);
      const LoopVerification v = verify_loop(query.keyframe.distributions, submap, initial,
                                             config.verification, M_PI / config.place.sectors);
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
      const double sr = config.verification.rotation_sigma_deg * kDegToRad;
      const double st = config.verification.translation_sigma;
      Vector6d info;
      info << 1.0 / (sr * sr), 1.0 / (sr * sr), 1.0 / (sr * sr), 1.0 / (st * st), 1.0 / (st * st),
          1.0 / (st * st);
      edge.information = info.asDiagonal();
      add_loop(edge);
      if (new_loops) new_loops->push_back(edge);
      return;
    }
  }

  void add_loop(const LoopEdge& edge) {
    const std::string a = anchor_of(edge.from.stream);
    const std::string b = anchor_of(edge.to.stream);
    if (a != b) {
      // Two groups meet: move the later group rigidly onto the earlier one's frame through
      // this loop, so the optimiser starts near the answer.
      const bool keep_a = starts_before(a, b);
      const std::string& keep = keep_a ? a : b;
      const std::string& moved = keep_a ? b : a;
      const Entry& from = entries.at(edge.from);
      const Entry& to = entries.at(edge.to);
      Eigen::Isometry3d correction;
      if (keep_a) {
        correction = from.pose * edge.relative * to.pose.inverse();
      } else {
        correction = to.pose * edge.relative.inverse() * from.pose.inverse();
      }
      for (auto& [key, entry] : entries)
        if (anchor_of(key.stream) == moved) entry.pose = correction * entry.pose;
      streams.at(moved).parent = keep;
    }
    loops.push_back(edge);
    loop_checked.push_back(false);
    ++loops_since_optimize;
  }

  /// Poses before the last optimisation, to undo it.
  std::vector<Eigen::Isometry3d> saved_poses;

  void restore_poses() {
    std::size_t i = 0;
    for (auto& [key, entry] : entries) entry.pose = saved_poses[i++];
  }

  Vector6d odometry_sigma(double distance) const {
    const PoseGraphConfig& g = config.graph;
    const double st =
        std::max(g.odometry_translation_sigma_min, g.odometry_translation_sigma_per_m * distance);
    const double sr = std::max(g.odometry_rotation_sigma_min_deg,
                               g.odometry_rotation_sigma_deg_per_m * distance) *
                      kDegToRad;
    Vector6d sigma;
    sigma << st, st, st, sr, sr, sr;
    return sigma;
  }

  /// The odometry edge from keyframe a to the next present keyframe b of its stream: its
  /// uncertainty by distance, or from b's tracker covariance (PoseGraphConfig::
  /// odometry_covariance). b's covariance is relative to a only when b directly follows a (no
  /// keyframe missing in between); otherwise, and when b has none, by distance.
  void set_odometry_uncertainty(PoseGraphEdge& e, const Keyframe& a, const Keyframe& b) const {
    const PoseGraphConfig& g = config.graph;
    e.sigma = odometry_sigma(e.relative.translation().norm());
    if (g.odometry_covariance != OdometryCovariance::kTracker || b.covariance.isZero(0.0) ||
        b.key.id != a.key.id + 1)
      return;
    Matrix6d c = relative_pose_covariance(a.odom_pose, b.odom_pose, b.covariance) *
                 (g.tracker_covariance_scale * g.tracker_covariance_scale);
    const double st = g.tracker_translation_sigma_min;
    const double sr = g.tracker_rotation_sigma_min_deg * kDegToRad;
    c.diagonal() += Vector6d(st * st, st * st, st * st, sr * sr, sr * sr, sr * sr);
    if (c.allFinite() && c.llt().info() == Eigen::Success) e.covariance = c;
  }

  static Vector6d loop_sigma(const LoopEdge& loop) {
    // LoopEdge information is in (phi, tau) order; the graph's sigma in (t, phi) order.
    const Vector6d info = loop.information.diagonal();
    Vector6d sigma;
    sigma << info.tail<3>().cwiseSqrt().cwiseInverse(), info.head<3>().cwiseSqrt().cwiseInverse();
    return sigma;
  }

  /// The loop's residual at the current poses is within loop_consistency_sigmas.
  bool consistent(const LoopEdge& loop) const {
    const Eigen::Isometry3d estimate =
        entries.at(loop.from).pose.inverse() * entries.at(loop.to).pose;
    const Eigen::Isometry3d error = loop.relative.inverse() * estimate;
    const Vector6d sigma = loop_sigma(loop);
    const double t = error.translation().norm() / sigma.head<3>().maxCoeff();
    const double r = Eigen::AngleAxisd(error.rotation()).angle() / sigma.tail<3>().maxCoeff();
    return std::max(t, r) <= config.graph.loop_consistency_sigmas;
  }

  /// One solve of the whole graph: odometry edges between consecutive keyframes of each
  /// stream, loop edges (robust once checked), one fixed node per group of streams.
  PoseGraphResult optimize_once(OptimizeSummary& summary) {
    std::map<KeyframeKey, int> index;
    std::vector<Eigen::Isometry3d> poses;
    saved_poses.clear();
    for (auto& [key, entry] : entries) {
      index.emplace(key, static_cast<int>(poses.size()));
      poses.push_back(entry.pose);
      saved_poses.push_back(entry.pose);
    }
    std::vector<bool> fixed(poses.size(), false);
    for (const auto& [name, stream] : streams) {
      if (stream.parent != name || stream.path_length.empty()) continue;
      fixed[static_cast<std::size_t>(index.at({name, stream.path_length.begin()->first}))] = true;
    }
    std::vector<PoseGraphEdge> edges;
    for (const auto& [name, stream] : streams) {
      const Entry* previous = nullptr;
      for (const auto& [id, path] : stream.path_length) {
        const Entry& entry = entries.at({name, id});
        if (previous) {
          PoseGraphEdge e;
          e.from = index.at(previous->keyframe.key);
          e.to = index.at(entry.keyframe.key);
          e.relative = previous->keyframe.odom_pose.inverse() * entry.keyframe.odom_pose;
          set_odometry_uncertainty(e, previous->keyframe, entry.keyframe);
          edges.push_back(e);
          ++summary.odometry_edges;
        }
        previous = &entry;
      }
    }
    for (std::size_t i = 0; i < loops.size(); ++i) {
      PoseGraphEdge e;
      e.from = index.at(loops[i].from);
      e.to = index.at(loops[i].to);
      e.relative = loops[i].relative;
      e.sigma = loop_sigma(loops[i]);
      e.robust = loop_checked[i];
      edges.push_back(e);
      ++summary.loop_edges;
    }
    const PoseGraphResult result = optimize_pose_graph(poses, fixed, edges, config.graph);
    if (result.usable) {
      for (auto& [key, entry] : entries)
        entry.pose = poses[static_cast<std::size_t>(index.at(key))];
    }
    summary.keyframes = static_cast<int>(poses.size());
    return result;
  }
};

Mapper::Mapper(const MapperConfig& config) : impl_(std::make_unique<Impl>(config)) {}
Mapper::~Mapper() = default;
Mapper::Mapper(Mapper&&) noexcept = default;
Mapper& Mapper::operator=(Mapper&&) noexcept = default;

AddStatus Mapper::add_keyframe(Keyframe keyframe, std::vector<LoopEdge>* new_loops) {
  Impl& m = *impl_;
  if (m.entries.count(keyframe.key)) {
    ++m.stats.duplicates;
    return AddStatus::kDuplicate;
  }
  const std::string name = keyframe.key.stream;
  auto [stream_it, new_stream] = m.streams.try_emplace(name);
  Impl::Stream& stream = stream_it->second;
  if (new_stream) stream.parent = name;
  if (new_stream || std::tie(keyframe.stamp.nanoseconds, keyframe.key.id) <
                        std::tie(stream.first_stamp_ns, stream.first_id)) {
    stream.first_stamp_ns = keyframe.stamp.nanoseconds;
    stream.first_id = keyframe.key.id;
  }
  const KeyframeKey key = keyframe.key;
  Impl::Entry entry;
  const double t0 = thread_cpu_seconds();
  entry.descriptor = make_place_descriptor(keyframe.distributions, m.config.place);
  const double t1 = thread_cpu_seconds();
  m.cpu.descriptor_s += t1 - t0;
  entry.keyframe = std::move(keyframe);
  // Chain from a neighbour before this keyframe is listed among the stream's ids.
  entry.pose = m.initial_pose(entry.keyframe);
  const Impl::Entry& stored = m.entries.emplace(key, std::move(entry)).first->second;
  stream_it->second.path_length.emplace(key.id, 0.0);
  m.update_path_lengths(stream_it->second, name);
  ++m.stats.keyframes;
  m.cpu.chain_s += thread_cpu_seconds() - t1;
  m.detect_loops(stored, new_loops);
  return AddStatus::kAdded;
}

OptimizeSummary Mapper::optimize() {
  Impl& m = *impl_;
  OptimizeSummary summary;
  if (m.loops_since_optimize == 0) return summary;
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = thread_cpu_seconds();
  PoseGraphResult result = m.optimize_once(summary);
  // New loops that the graph cannot accommodate are dropped and the graph solved again
  // without them, from the poses before.
  std::vector<std::size_t> inconsistent;
  for (std::size_t i = 0; i < m.loops.size(); ++i)
    if (!m.loop_checked[i] && !m.consistent(m.loops[i])) inconsistent.push_back(i);
  if (!inconsistent.empty()) {
    for (auto it = inconsistent.rbegin(); it != inconsistent.rend(); ++it) {
      m.loops.erase(m.loops.begin() + static_cast<std::ptrdiff_t>(*it));
      m.loop_checked.erase(m.loop_checked.begin() + static_cast<std::ptrdiff_t>(*it));
      --m.stats.verified;
      ++m.stats.rejected;
      ++m.stats.inconsistent;
    }
    m.restore_poses();
    summary = OptimizeSummary{};
    result = m.optimize_once(summary);
  }
  std::fill(m.loop_checked.begin(), m.loop_checked.end(), true);
  m.loops_since_optimize = 0;
  ++m.stats.optimizations;
  summary.ran = true;
  summary.iterations = result.iterations;
  summary.initial_cost = result.initial_cost;
  summary.final_cost = result.final_cost;
  summary.milliseconds = elapsed_ms(start);
  m.cpu.optimize_s += thread_cpu_seconds() - cpu_start;
  return summary;
}

bool Mapper::contains(const KeyframeKey& key) const {
  return impl_->entries.count(key) > 0;
}

const Keyframe* Mapper::keyframe(const KeyframeKey& key) const {
  auto it = impl_->entries.find(key);
  return it == impl_->entries.end() ? nullptr : &it->second.keyframe;
}

std::vector<KeyframePose> Mapper::poses() const {
  std::vector<KeyframePose> out;
  out.reserve(impl_->entries.size());
  for (const auto& [key, entry] : impl_->entries)
    out.push_back({key, entry.pose, impl_->anchor_of(key.stream)});
  return out;
}

std::optional<KeyframePose> Mapper::pose(const KeyframeKey& key) const {
  auto it = impl_->entries.find(key);
  if (it == impl_->entries.end()) return std::nullopt;
  return KeyframePose{key, it->second.pose, impl_->anchor_of(key.stream)};
}

std::optional<KeyframePose> Mapper::correction(const std::string& stream,
                                               std::optional<std::uint64_t> id) const {
  auto s = impl_->streams.find(stream);
  if (s == impl_->streams.end() || s->second.path_length.empty()) return std::nullopt;
  const auto& ids = s->second.path_length;
  auto it = id ? ids.upper_bound(*id) : ids.end();
  if (it == ids.begin()) it = std::next(it);  // before the first keyframe: use the first
  const KeyframeKey key{stream, std::prev(it)->first};
  const auto& entry = impl_->entries.at(key);
  return KeyframePose{key, entry.pose * entry.keyframe.odom_pose.inverse(),
                      impl_->anchor_of(stream)};
}

std::string Mapper::map_anchor() const {
  const std::string first = impl_->first_stream();
  return first.empty() ? first : impl_->anchor_of(first);
}

const std::vector<LoopEdge>& Mapper::loops() const {
  return impl_->loops;
}

MapperStats Mapper::stats() const {
  MapperStats s = impl_->stats;
  s.streams = impl_->streams.size();
  return s;
}

MapperCpu Mapper::cpu() const {
  return impl_->cpu;
}

const MapperConfig& Mapper::config() const {
  return impl_->config;
}

std::vector<Distribution> Mapper::global_map() const {
  const Impl& m = *impl_;
  VoxelizerConfig voxels;
  voxels.voxel_size = m.config.map_voxel_size;
  VoxelMap map(voxels, VoxelMapConfig{});
  if (m.streams.empty()) return {};
  const std::string anchor = m.anchor_of(m.first_stream());
  // Every keyframe's moments moved to the map frame, merged in one insertion (VoxelMap
  // rebuilds its distributions after each insertion).
  GridVoxels all;
  for (const auto& [key, entry] : m.entries) {
    if (m.anchor_of(key.stream) != anchor) continue;
    const Eigen::Matrix3d r = entry.pose.linear();
    const Eigen::Vector3d t = entry.pose.translation();
    for (const VoxelMoments& moments : moments_of(entry.keyframe.distributions).moments)
      all.moments.push_back(moments.transformed(r, t, entry.pose * moments.origin));
  }
  map.insert(all, Eigen::Isometry3d::Identity());
  return map.distributions();
}

}  // namespace litamin2::mapping

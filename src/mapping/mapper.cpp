#include "litamin2/mapping/mapper.hpp"

#include "litamin2/core/stopwatch.hpp"
#include "litamin2/core/voxel_map.hpp"
#include "litamin2/mapping/distribution_moments.hpp"
#include "litamin2/mapping/loop_detector.hpp"
#include "litamin2/mapping/odometry_covariance.hpp"
#include "litamin2/mapping/pose_graph.hpp"
#include "litamin2/mapping/stream_groups.hpp"

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>
#include <tuple>

namespace litamin2::mapping {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

}  // namespace

struct Mapper::Impl {
  explicit Impl(const MapperConfig& c) : config((validate(c), c)), detector(config) {}

  MapperConfig config;
  MapperEntries entries;
  StreamGroups groups;
  LoopDetector detector;
  std::vector<LoopEdge> loops;
  /// loops[i] went through one optimisation and was consistent: it gets the robust loss.
  std::vector<bool> loop_checked;
  MapperStats stats;
  MapperCpu cpu;
  int loops_since_optimize = 0;

  void update_path_lengths(StreamGroups::Stream& stream, const std::string& name) {
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
    const StreamGroups::Stream& stream = groups.at(kf.key.stream);
    auto next = stream.path_length.upper_bound(kf.key.id);
    const MapperEntry* neighbour = nullptr;
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

  void add_loop(const LoopEdge& edge) {
    const std::string a = groups.anchor_of(edge.from.stream);
    const std::string b = groups.anchor_of(edge.to.stream);
    if (a != b) {
      // Two groups meet: move the later group rigidly onto the earlier one's frame through
      // this loop, so the optimiser starts near the answer.
      const bool keep_a = groups.starts_before(a, b);
      const std::string& moved = keep_a ? b : a;
      const MapperEntry& from = entries.at(edge.from);
      const MapperEntry& to = entries.at(edge.to);
      Eigen::Isometry3d correction;
      if (keep_a) {
        correction = from.pose * edge.relative * to.pose.inverse();
      } else {
        correction = to.pose * edge.relative.inverse() * from.pose.inverse();
      }
      for (auto& [key, entry] : entries)
        if (groups.anchor_of(key.stream) == moved) entry.pose = correction * entry.pose;
      groups.join(a, b);
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
    for (const auto& [name, stream] : groups.streams()) {
      if (stream.parent != name || stream.path_length.empty()) continue;
      fixed[static_cast<std::size_t>(index.at({name, stream.path_length.begin()->first}))] = true;
    }
    std::vector<PoseGraphEdge> edges;
    for (const auto& [name, stream] : groups.streams()) {
      const MapperEntry* previous = nullptr;
      for (const auto& [id, path] : stream.path_length) {
        const MapperEntry& entry = entries.at({name, id});
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
  const KeyframeKey key = keyframe.key;
  StreamGroups::Stream& stream = m.groups.add(key, keyframe.stamp);
  MapperEntry entry;
  const double t0 = thread_cpu_seconds();
  entry.descriptor = make_place_descriptor(keyframe.distributions, m.config.place);
  const double t1 = thread_cpu_seconds();
  m.cpu.descriptor_s += t1 - t0;
  entry.keyframe = std::move(keyframe);
  // Chained from the nearest other keyframe of the stream (initial_pose skips its own id).
  entry.pose = m.initial_pose(entry.keyframe);
  const MapperEntry& stored = m.entries.emplace(key, std::move(entry)).first->second;
  m.update_path_lengths(stream, key.stream);
  ++m.stats.keyframes;
  m.cpu.chain_s += thread_cpu_seconds() - t1;
  if (const auto loop = m.detector.detect(stored, m.entries, m.groups, m.stats, m.cpu)) {
    m.add_loop(*loop);
    if (new_loops) new_loops->push_back(*loop);
  }
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
    out.push_back({key, entry.pose, impl_->groups.anchor_of(key.stream)});
  return out;
}

std::optional<KeyframePose> Mapper::pose(const KeyframeKey& key) const {
  auto it = impl_->entries.find(key);
  if (it == impl_->entries.end()) return std::nullopt;
  return KeyframePose{key, it->second.pose, impl_->groups.anchor_of(key.stream)};
}

std::optional<KeyframePose> Mapper::correction(const std::string& stream,
                                               std::optional<std::uint64_t> id) const {
  const auto& streams = impl_->groups.streams();
  auto s = streams.find(stream);
  if (s == streams.end() || s->second.path_length.empty()) return std::nullopt;
  const auto& ids = s->second.path_length;
  auto it = id ? ids.upper_bound(*id) : ids.end();
  if (it == ids.begin()) it = std::next(it);  // before the first keyframe: use the first
  const KeyframeKey key{stream, std::prev(it)->first};
  const auto& entry = impl_->entries.at(key);
  return KeyframePose{key, entry.pose * entry.keyframe.odom_pose.inverse(),
                      impl_->groups.anchor_of(stream)};
}

std::string Mapper::map_anchor() const {
  const std::string first = impl_->groups.first_stream();
  return first.empty() ? first : impl_->groups.anchor_of(first);
}

const std::vector<LoopEdge>& Mapper::loops() const {
  return impl_->loops;
}

MapperStats Mapper::stats() const {
  MapperStats s = impl_->stats;
  s.streams = impl_->groups.streams().size();
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
  if (m.groups.streams().empty()) return {};
  const std::string anchor = m.groups.anchor_of(m.groups.first_stream());
  // Every keyframe's moments moved to the map frame, merged in one insertion (VoxelMap
  // rebuilds its distributions after each insertion).
  GridVoxels all;
  for (const auto& [key, entry] : m.entries) {
    if (m.groups.anchor_of(key.stream) != anchor) continue;
    const Eigen::Matrix3d r = entry.pose.linear();
    const Eigen::Vector3d t = entry.pose.translation();
    for (const VoxelMoments& moments : moments_of(entry.keyframe.distributions).moments)
      all.moments.push_back(moments.transformed(r, t, entry.pose * moments.origin));
  }
  map.insert(all, Eigen::Isometry3d::Identity());
  return map.distributions();
}

}  // namespace litamin2::mapping

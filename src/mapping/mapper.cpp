#include "litamin2/mapping/mapper.hpp"

#include "litamin2/core/stopwatch.hpp"
#include "litamin2/core/voxel_map.hpp"
#include "litamin2/mapping/distribution_moments.hpp"
#include "litamin2/mapping/loop_detector.hpp"
#include "litamin2/mapping/merge_confirmation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>

namespace litamin2::mapping {

struct Mapper::Impl {
  Impl(const MapperConfig& c, std::unique_ptr<DistributionCache> distribution_cache)
      : config((validate(c), c)),
        graph(config.place.rings, config.place.proximity_cell_size),
        cache(distribution_cache ? std::move(distribution_cache)
                                 : std::make_unique<DistributionCache>()),
        detector(config),
        drift(config.graph),
        optimizer(config, &drift),
        merges(config.place) {}

  MapperConfig config;
  KeyframeGraph graph;
  std::unique_ptr<DistributionCache> cache;
  LoopDetector detector;
  /// Each stream's odometry yaw drift, taken out of its odometry edges (yaw_drift.hpp).
  YawDriftEstimator drift;
  GraphOptimizer optimizer;
  MergeConfirmation merges;
  GraphLoops loops;
  MapperStats stats;
  MapperCpu cpu;
  /// keep_descriptor_cells_outside was called: nodes hold no descriptor cells.
  bool cells_outside = false;
  int loops_since_optimize = 0;
  std::size_t checked_since_full_pass = 0;
  /// Full-pass problems made (each shifts the segments' cuts).
  std::size_t full_pass_problems = 0;
  /// Per stream, the path length at its latest place search (search_spacing).
  std::vector<double> last_search;

  /// Initial pose of a new keyframe: chained by odometry (without the stream's yaw drift)
  /// from its nearest present neighbour in the same stream, else its odometry pose.
  Eigen::Isometry3d initial_pose(const Keyframe& kf) const {
    const StreamGroups& groups = graph.groups();
    if (!groups.contains(kf.key.stream)) return kf.odom_pose;
    const std::uint32_t stream = groups.index(kf.key.stream);
    const auto& chain = groups.at(kf.key.stream).nodes;
    auto next = chain.upper_bound(kf.key.id);
    const KeyframeNode* neighbour = nullptr;
    if (next != chain.begin()) neighbour = &graph.node(std::prev(next)->second);
    if (!neighbour && next != chain.end()) neighbour = &graph.node(next->second);
    if (!neighbour) return kf.odom_pose;
    const Eigen::Isometry3d relative = neighbour->odom_pose.inverse() * kf.odom_pose;
    const double distance = relative.translation().norm();
    return neighbour->pose *
           without_yaw_drift(relative, drift.drift_per_m(stream),
                             kf.key.id > neighbour->key.id ? distance : -distance);
  }

  /// The loops from `first` on were just checked: their ends are loop ends of their streams
  /// from now on, and those streams' drift is estimated again.
  void estimate_drift_from(std::size_t first) {
    if (!drift.enabled()) return;
    std::vector<std::uint32_t> streams;
    for (std::size_t i = first; i < loops.size(); ++i)
      for (const std::uint32_t n : {loops.nodes[i].first, loops.nodes[i].second}) {
        drift.add_anchor(graph, n);
        streams.push_back(graph.node(n).stream);
      }
    std::sort(streams.begin(), streams.end());
    streams.erase(std::unique(streams.begin(), streams.end()), streams.end());
    for (const std::uint32_t s : streams) drift.update(graph, s);
  }

  /// Adds a verified loop; one between two groups goes through the merge confirmation
  /// first. Appends the loops added to `added` (none while a merge waits to be confirmed).
  void offer_loop(const LoopEdge& edge, std::vector<LoopEdge>* added) {
    const auto from = static_cast<std::uint32_t>(graph.find(edge.from));
    const auto to = static_cast<std::uint32_t>(graph.find(edge.to));
    const StreamGroups& groups = graph.groups();
    if (groups.anchor_of(graph.node(from).stream) == groups.anchor_of(graph.node(to).stream)) {
      add_loop(edge);
      if (added) added->push_back(edge);
      return;
    }
    const std::vector<MergeCandidate> confirmed = merges.offer({edge, from, to}, graph);
    if (confirmed.empty()) {
      ++stats.merges_pending;
      return;
    }
    ++stats.merges;
    // The earlier loops join the groups (the first one moves the later group), the newest
    // is then a loop inside the group.
    for (const MergeCandidate& c : confirmed) {
      add_loop(c.edge);
      if (added) added->push_back(c.edge);
    }
  }

  void add_loop(const LoopEdge& edge) {
    const auto from = static_cast<std::uint32_t>(graph.find(edge.from));
    const auto to = static_cast<std::uint32_t>(graph.find(edge.to));
    StreamGroups& groups = graph.groups();
    const std::uint32_t a = groups.anchor_of(graph.node(from).stream);
    const std::uint32_t b = groups.anchor_of(graph.node(to).stream);
    if (a != b) {
      // Two groups meet: move the later group rigidly onto the earlier one's frame through
      // this loop, so the optimiser starts near the answer.
      const bool keep_a = groups.starts_before(a, b);
      const std::uint32_t moved = keep_a ? b : a;
      const Eigen::Isometry3d& pf = graph.node(from).pose;
      const Eigen::Isometry3d& pt = graph.node(to).pose;
      const Eigen::Isometry3d correction =
          keep_a ? Eigen::Isometry3d(pf * edge.relative * pt.inverse())
                 : Eigen::Isometry3d(pt * edge.relative.inverse() * pf.inverse());
      for (std::uint32_t s = 0; s < groups.streams().size(); ++s) {
        if (groups.anchor_of(s) != moved) continue;
        for (const auto& [id, n] : groups.at(s).nodes)
          graph.set_pose(n, correction * graph.node(n).pose);
      }
      groups.join(a, b);
    }
    loops.add(edge, from, to);
    ++loops_since_optimize;
  }

  /// The streams that node `query`'s stream closed a checked loop with in the
  /// proximity_partner_gap metres of its path before the query, sorted (LoopDetector). Only a
  /// search of all keyframes with a proximity radius reads them: other scopes get none.
  std::vector<std::uint32_t> recent_partners(std::uint32_t query, SearchScope scope) const {
    std::vector<std::uint32_t> partners;
    const double gap = config.place.proximity_partner_gap;
    if (gap <= 0.0 || scope != SearchScope::kAll || config.place.proximity_radius <= 0.0)
      return partners;
    const KeyframeNode& q = graph.node(query);
    const auto& chain = graph.groups().at(q.stream).nodes;
    for (auto it = chain.find(q.key.id); it != chain.begin();) {
      --it;
      if (q.path_length - graph.node(it->second).path_length > gap) break;
      const auto at = loops.at_node.find(it->second);
      if (at == loops.at_node.end()) continue;
      for (const std::uint32_t e : at->second) {
        const auto [from, to] = loops.nodes[e];
        partners.push_back(graph.node(from == it->second ? to : from).stream);
      }
    }
    std::sort(partners.begin(), partners.end());
    partners.erase(std::unique(partners.begin(), partners.end()), partners.end());
    return partners;
  }

  /// Per stream, the path length at its latest verified loop (loop_spacing).
  std::vector<double> last_loop;
  /// Verifications left to searches of all keyframes (verification_budget_per_keyframe).
  double verification_allowance = 0.0;

  /// Whether the stream's new keyframe at `path` is due a place search (search_spacing), and
  /// in which keyframes: within loop_spacing after the stream's latest loop inside its group,
  /// only other groups'.
  std::optional<SearchScope> search_due(std::uint32_t stream, double path) {
    if (config.place.search_spacing > 0.0) {
      if (last_search.size() <= stream) last_search.resize(stream + 1, -1e300);
      if (std::abs(path - last_search[stream]) < config.place.search_spacing) return std::nullopt;
      last_search[stream] = path;
    }
    if (config.place.loop_spacing > 0.0 && stream < last_loop.size() && path >= last_loop[stream] &&
        path - last_loop[stream] < config.place.loop_spacing)
      return SearchScope::kOtherGroups;
    if (config.place.verification_budget_per_keyframe > 0.0 && verification_allowance < 1.0) {
      ++stats.searches_over_budget;
      return SearchScope::kOtherGroups;
    }
    return SearchScope::kAll;
  }
};

Mapper::Mapper(const MapperConfig& config, std::unique_ptr<DistributionCache> cache)
    : impl_(std::make_unique<Impl>(config, std::move(cache))) {}
Mapper::~Mapper() = default;
Mapper::Mapper(Mapper&&) noexcept = default;
Mapper& Mapper::operator=(Mapper&&) noexcept = default;

PlaceDescriptor Mapper::describe(const std::vector<Distribution>& distributions) const {
  return make_place_descriptor(distributions, impl_->config.place);
}

AddStatus Mapper::add_keyframe(Keyframe keyframe, std::vector<LoopEdge>* new_loops,
                               const PlaceDescriptor* descriptor) {
  Impl& m = *impl_;
  if (m.graph.find(keyframe.key) >= 0) {
    ++m.stats.duplicates;
    return AddStatus::kDuplicate;
  }
  const double t0 = thread_cpu_seconds();
  KeyframeNode node;
  node.descriptor = descriptor ? *descriptor : describe(keyframe.distributions);
  const double t1 = thread_cpu_seconds();
  m.cpu.descriptor_s += t1 - t0;
  node.key = keyframe.key;
  node.stamp = keyframe.stamp;
  node.voxel_size = keyframe.voxel_size;
  node.odom_pose = keyframe.odom_pose;
  node.covariance = keyframe.covariance.cast<float>();
  // Chained from the nearest other keyframe of the stream.
  node.pose = m.initial_pose(keyframe);
  const std::uint32_t index = m.graph.add(std::move(node));
  ++m.stats.keyframes;
  m.cpu.chain_s += thread_cpu_seconds() - t1;
  const KeyframeNode& stored = m.graph.node(index);
  const double budget = m.config.place.verification_budget_per_keyframe;
  if (budget > 0.0)
    m.verification_allowance = std::min(m.verification_allowance + budget, 100.0 * budget);
  if (const auto scope = m.search_due(stored.stream, stored.path_length)) {
    const std::size_t candidates_before = m.stats.candidates;
    const auto loop = m.detector.detect(index, keyframe.distributions, m.graph, *m.cache, m.stats,
                                        m.cpu, *scope, m.recent_partners(index, *scope));
    if (budget > 0.0 && *scope == SearchScope::kAll)
      m.verification_allowance -= static_cast<double>(m.stats.candidates - candidates_before);
    if (loop) {
      const StreamGroups& groups = m.graph.groups();
      const KeyframeNode& from = m.graph.node(static_cast<std::uint32_t>(m.graph.find(loop->from)));
      if (groups.anchor_of(from.stream) == groups.anchor_of(stored.stream)) {
        // A loop inside the group holds the drift: the next ones wait loop_spacing metres.
        if (m.last_loop.size() <= stored.stream) m.last_loop.resize(stored.stream + 1, -1e300);
        m.last_loop[stored.stream] = stored.path_length;
      }
      m.offer_loop(*loop, new_loops);
    }
  }
  if (m.cells_outside) release_cells(m.graph.mutable_node(index).descriptor);
  m.cache->put(keyframe.key, std::move(keyframe.distributions));
  return AddStatus::kAdded;
}

OptimizeSummary Mapper::optimize() {
  Impl& m = *impl_;
  OptimizeSummary summary;
  if (m.loops_since_optimize == 0) return summary;
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = thread_cpu_seconds();
  const std::size_t before = m.loops.size();
  const LocalOptimization local = m.optimizer.optimize_local(m.graph, m.loops, m.stats);
  const std::size_t first_new = before - static_cast<std::size_t>(m.loops_since_optimize);
  m.checked_since_full_pass += m.loops.size() - first_new;
  m.estimate_drift_from(first_new);
  m.loops_since_optimize = 0;
  ++m.stats.optimizations;
  summary.ran = local.ran;
  summary.keyframes = local.keyframes;
  summary.odometry_edges = local.odometry_edges;
  summary.loop_edges = local.loop_edges;
  summary.iterations = local.iterations;
  summary.held_ends = local.held_ends;
  summary.free_keyframes = local.free;
  summary.bounded_keyframes = local.bounded;
  summary.widened = local.widened;
  summary.initial_cost = local.initial_cost;
  summary.final_cost = local.final_cost;
  summary.milliseconds = elapsed_ms(start);
  m.cpu.optimize_s += thread_cpu_seconds() - cpu_start;
  return summary;
}

OptimizeSummary Mapper::optimize_full() {
  OptimizeSummary summary = optimize();
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = thread_cpu_seconds();
  FullPassProblem problem = full_pass_problem();
  GraphOptimizer::solve_full_pass(problem);
  apply_full_pass(problem);
  impl_->cpu.full_pass_s += thread_cpu_seconds() - cpu_start;
  summary.ran = true;
  summary.keyframes = static_cast<int>(impl_->graph.size());
  summary.loop_edges = static_cast<int>(problem.loop_edges);
  summary.iterations = problem.result.iterations;
  summary.initial_cost = problem.result.initial_cost;
  summary.final_cost = problem.result.final_cost;
  summary.milliseconds += elapsed_ms(start);
  return summary;
}

FullPassProblem Mapper::full_pass_problem() const {
  impl_->checked_since_full_pass = 0;
  return impl_->optimizer.full_pass_problem(impl_->graph, impl_->loops,
                                            impl_->full_pass_problems++);
}

void Mapper::apply_full_pass(const FullPassProblem& problem) {
  const PoseGraphConfig& g = impl_->config.graph;
  impl_->stats.full_pass_keyframes_moved += GraphOptimizer::apply_full_pass(
      problem, impl_->graph, g.full_pass_min_shift, g.full_pass_min_turn_deg * M_PI / 180.0);
  if (problem.result.usable) {
    ++impl_->stats.full_passes;
    impl_->drift.update_all(impl_->graph);
  }
  if (problem.result.diverged) ++impl_->stats.diverged;
}

std::size_t Mapper::loops_since_full_pass() const {
  return impl_->checked_since_full_pass;
}

void Mapper::keep_descriptor_cells_outside(DescriptorLoader loader) {
  Impl& m = *impl_;
  m.detector.set_descriptor_loader(std::move(loader));
  m.cells_outside = true;
  for (std::uint32_t n = 0; n < m.graph.size(); ++n)
    release_cells(m.graph.mutable_node(n).descriptor);
}

std::size_t Mapper::descriptor_loads() const {
  return impl_->detector.descriptor_loads();
}

void Mapper::restore(std::vector<KeyframeNode> nodes, const std::vector<LoopEdge>& loops,
                     const std::vector<LoopEdge>& pending_merges) {
  Impl& m = *impl_;
  if (m.graph.size() != 0) throw std::logic_error("Mapper::restore: the mapper is not empty");
  m.graph.reserve(nodes.size());
  m.loops.edges.reserve(loops.size());
  m.loops.nodes.reserve(loops.size());
  for (KeyframeNode& node : nodes) {
    if (m.graph.find(node.key) >= 0) {
      ++m.stats.duplicates;
      continue;
    }
    m.graph.add(std::move(node));
    ++m.stats.keyframes;
  }
  StreamGroups& groups = m.graph.groups();
  for (const LoopEdge& edge : loops) {
    const std::int64_t from = m.graph.find(edge.from), to = m.graph.find(edge.to);
    if (from < 0 || to < 0)
      throw std::invalid_argument("Mapper::restore: a loop edge's keyframe is missing");
    const std::uint32_t a = groups.anchor_of(m.graph.node(static_cast<std::uint32_t>(from)).stream);
    const std::uint32_t b = groups.anchor_of(m.graph.node(static_cast<std::uint32_t>(to)).stream);
    if (a != b) groups.join(a, b);
    m.loops.add(edge, static_cast<std::uint32_t>(from), static_cast<std::uint32_t>(to));
    ++m.stats.verified;
  }
  m.loops.check_all(m.graph);
  m.checked_since_full_pass = m.loops.size();
  m.estimate_drift_from(0);
  std::vector<MergeCandidate> pending;
  for (const LoopEdge& edge : pending_merges) {
    const std::int64_t from = m.graph.find(edge.from), to = m.graph.find(edge.to);
    if (from < 0 || to < 0)
      throw std::invalid_argument("Mapper::restore: a pending merge's keyframe is missing");
    pending.push_back({edge, static_cast<std::uint32_t>(from), static_cast<std::uint32_t>(to)});
  }
  m.merges.restore(pending, m.graph);
}

std::vector<LoopEdge> Mapper::pending_merges() const {
  std::vector<LoopEdge> out;
  for (const MergeCandidate& c : impl_->merges.pending_loops()) out.push_back(c.edge);
  return out;
}

std::uint64_t Mapper::pending_merges_version() const {
  return impl_->merges.version();
}

bool Mapper::contains(const KeyframeKey& key) const {
  return impl_->graph.find(key) >= 0;
}

const KeyframeNode* Mapper::node(const KeyframeKey& key) const {
  const std::int64_t n = impl_->graph.find(key);
  return n < 0 ? nullptr : &impl_->graph.node(static_cast<std::uint32_t>(n));
}

const KeyframeGraph& Mapper::graph() const {
  return impl_->graph;
}

DistributionCache& Mapper::cache() const {
  return *impl_->cache;
}

std::vector<std::uint32_t> Mapper::take_changed() {
  return impl_->graph.take_changed();
}

std::vector<KeyframePose> Mapper::poses() const {
  const KeyframeGraph& g = impl_->graph;
  std::vector<KeyframePose> out;
  out.reserve(g.size());
  for (const auto& [key, n] : g.by_key()) {
    const KeyframeNode& node = g.node(n);
    out.push_back({key, node.pose, g.groups().at(g.groups().anchor_of(node.stream)).name});
  }
  return out;
}

std::optional<KeyframePose> Mapper::pose(const KeyframeKey& key) const {
  const KeyframeNode* n = node(key);
  if (!n) return std::nullopt;
  const StreamGroups& groups = impl_->graph.groups();
  return KeyframePose{key, n->pose, groups.at(groups.anchor_of(n->stream)).name};
}

std::optional<KeyframePose> Mapper::correction(const std::string& stream,
                                               std::optional<std::uint64_t> id) const {
  const StreamGroups& groups = impl_->graph.groups();
  if (!groups.contains(stream)) return std::nullopt;
  const auto& ids = groups.at(stream).nodes;
  if (ids.empty()) return std::nullopt;
  auto it = id ? ids.upper_bound(*id) : ids.end();
  if (it == ids.begin()) it = std::next(it);  // before the first keyframe: use the first
  const KeyframeNode& n = impl_->graph.node(std::prev(it)->second);
  return KeyframePose{n.key, n.pose * n.odom_pose.inverse(), groups.anchor_of(stream)};
}

std::string Mapper::map_anchor() const {
  const StreamGroups& groups = impl_->graph.groups();
  const std::string first = groups.first_stream();
  return first.empty() ? first : groups.anchor_of(first);
}

const std::vector<LoopEdge>& Mapper::loops() const {
  return impl_->loops.edges;
}

MapperStats Mapper::stats() const {
  MapperStats s = impl_->stats;
  s.streams = impl_->graph.groups().streams().size();
  s.yaw_drift_estimates = impl_->drift.estimates();
  s.yaw_drift_rejected = impl_->drift.rejected();
  return s;
}

MapperCpu Mapper::cpu() const {
  return impl_->cpu;
}

double Mapper::yaw_drift_per_m(const std::string& stream) const {
  const StreamGroups& groups = impl_->graph.groups();
  return groups.contains(stream) ? impl_->drift.drift_per_m(groups.index(stream)) : 0.0;
}

const MapperConfig& Mapper::config() const {
  return impl_->config;
}

std::vector<Distribution> Mapper::global_map() const {
  const Impl& m = *impl_;
  const StreamGroups& groups = m.graph.groups();
  if (groups.streams().empty()) return {};
  VoxelizerConfig voxels;
  voxels.voxel_size = m.config.map_voxel_size;
  VoxelMap map(voxels, VoxelMapConfig{});
  const std::uint32_t anchor = groups.anchor_of(groups.index(groups.first_stream()));
  // Every keyframe's moments moved to the map frame, merged in one insertion (VoxelMap
  // rebuilds its distributions after each insertion).
  GridVoxels all;
  for (const auto& [key, n] : m.graph.by_key()) {
    const KeyframeNode& node = m.graph.node(n);
    if (groups.anchor_of(node.stream) != anchor) continue;
    const Eigen::Matrix3d r = node.pose.linear();
    const Eigen::Vector3d t = node.pose.translation();
    for (const VoxelMoments& moments : moments_of(*m.cache->get(key)).moments)
      all.moments.push_back(moments.transformed(r, t, node.pose * moments.origin));
  }
  map.insert(all, Eigen::Isometry3d::Identity());
  return map.distributions();
}

}  // namespace litamin2::mapping

#include "litamin2/mapping/graph_optimizer.hpp"

#include "litamin2/core/stopwatch.hpp"
#include "litamin2/mapping/odometry_covariance.hpp"

#include <Eigen/Cholesky>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <set>

namespace litamin2::mapping {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

Vector6d loop_sigma(const LoopEdge& loop) {
  // LoopEdge information is in (phi, tau) order; the graph's sigma in (t, phi) order.
  const Vector6d info = loop.information.diagonal();
  Vector6d sigma;
  sigma << info.tail<3>().cwiseSqrt().cwiseInverse(), info.head<3>().cwiseSqrt().cwiseInverse();
  return sigma;
}

/// Local problem under construction: graph nodes -> problem indices.
struct LocalProblem {
  std::unordered_map<std::uint32_t, int> index;
  std::vector<std::uint32_t> nodes;
  std::vector<bool> fixed;

  int add(std::uint32_t node, bool is_fixed) {
    const auto [it, inserted] = index.try_emplace(node, static_cast<int>(nodes.size()));
    if (inserted) {
      nodes.push_back(node);
      fixed.push_back(is_fixed);
    }
    return it->second;
  }
  bool has(std::uint32_t node) const { return index.count(node) > 0; }
};

/// A set of graph nodes: a flag per node of the graph for membership (no tree to walk or
/// allocate per insertion), the members in a list; sorted() lists them in increasing order, as
/// a std::set would.
class NodeSet {
 public:
  explicit NodeSet(std::size_t graph_size) : in_(graph_size, 0) {}
  bool insert(std::uint32_t node) {
    if (in_[node]) return false;
    in_[node] = 1;
    members_.push_back(node);
    return true;
  }
  bool count(std::uint32_t node) const { return in_[node] != 0; }
  std::size_t size() const { return members_.size(); }
  /// The members in the order of insertion.
  const std::vector<std::uint32_t>& members() const { return members_; }
  const std::vector<std::uint32_t>& sorted() {
    std::sort(members_.begin(), members_.end());
    return members_;
  }

 private:
  std::vector<char> in_;
  std::vector<std::uint32_t> members_;
};

/// The part of the region `free` kept free under a bound of `limit` keyframes: the ends,
/// `stretches` (each new loop's newer end's stream from its latest anchored keyframe on: the
/// drift the loop corrects), every keyframe between two ends along a stream within the region
/// (never an interior hinge), and of the rest (the ends' local_hops neighbourhoods) those
/// nearest to an end by odometry edges along their streams, breadth first from every end at
/// once (each end gets an equal depth), while fewer than `limit` are kept. The ends, the
/// stretches and the keyframes between ends are kept even beyond the limit. The region is
/// connected along its streams to the ends (graph_optimizer.hpp), so every member is reached.
NodeSet nearest_free(const KeyframeGraph& graph, const NodeSet& free, const NodeSet& stretches,
                     const std::vector<std::uint32_t>& ends, std::size_t limit) {
  const StreamGroups& groups = graph.groups();
  NodeSet kept(graph.size()), is_end(graph.size());
  for (std::uint32_t n : stretches.members()) kept.insert(n);
  for (std::uint32_t n : ends) is_end.insert(n);
  // Between two ends: walk from each end in both directions within the region to the next.
  std::vector<std::uint32_t> walked;
  for (std::uint32_t n : ends) {
    kept.insert(n);
    const KeyframeNode& node = graph.node(n);
    const auto& chain = groups.at(node.stream).nodes;
    const auto at = chain.find(node.key.id);
    walked.clear();
    for (auto it = std::next(at); it != chain.end() && free.count(it->second); ++it) {
      if (is_end.count(it->second)) {
        for (std::uint32_t m : walked) kept.insert(m);
        break;
      }
      walked.push_back(it->second);
    }
    walked.clear();
    for (auto it = at; it != chain.begin();) {
      --it;
      if (!free.count(it->second)) break;
      if (is_end.count(it->second)) {
        for (std::uint32_t m : walked) kept.insert(m);
        break;
      }
      walked.push_back(it->second);
    }
  }
  // The outer tails, nearest first.
  NodeSet seen(graph.size());
  std::vector<std::uint32_t> frontier;
  for (std::uint32_t n : ends)
    if (seen.insert(n)) frontier.push_back(n);
  while (!frontier.empty() && kept.size() < limit) {
    std::vector<std::uint32_t> next;
    for (std::uint32_t n : frontier) {
      const KeyframeNode& node = graph.node(n);
      const auto& chain = groups.at(node.stream).nodes;
      const auto at = chain.find(node.key.id);
      auto visit = [&](std::uint32_t m) {
        if (!free.count(m) || !seen.insert(m)) return;
        if (kept.count(m) || kept.size() < limit) {
          kept.insert(m);
          next.push_back(m);
        }
      };
      if (at != chain.begin()) visit(std::prev(at)->second);
      if (std::next(at) != chain.end()) visit(std::next(at)->second);
    }
    frontier.swap(next);
  }
  return kept;
}

}  // namespace

void GraphLoops::add(const LoopEdge& edge, std::uint32_t from, std::uint32_t to) {
  edges.push_back(edge);
  nodes.emplace_back(from, to);
  checked.push_back(false);
}

void GraphLoops::check_all(KeyframeGraph& graph) {
  for (std::size_t i = 0; i < edges.size(); ++i) {
    if (checked[i]) continue;
    checked[i] = true;
    const auto [from, to] = nodes[i];
    at_node[from].push_back(static_cast<std::uint32_t>(i));
    if (to != from) at_node[to].push_back(static_cast<std::uint32_t>(i));
    graph.mutable_node(from).anchored = true;
    graph.mutable_node(to).anchored = true;
  }
}

PoseGraphEdge GraphOptimizer::odometry_edge(const KeyframeNode& a, const KeyframeNode& b) const {
  const PoseGraphConfig& g = config_.graph;
  PoseGraphEdge e;
  e.relative = a.odom_pose.inverse() * b.odom_pose;
  const double distance = e.relative.translation().norm();
  if (drift_)
    e.relative =
        without_yaw_drift(e.relative, drift_->drift_per_m(b.stream), b.path_length - a.path_length);
  const double st =
      std::max(g.odometry_translation_sigma_min, g.odometry_translation_sigma_per_m * distance);
  const double sr =
      std::max(g.odometry_rotation_sigma_min_deg, g.odometry_rotation_sigma_deg_per_m * distance) *
      kDegToRad;
  e.sigma << st, st, st, sr, sr, sr;
  const Matrix6d covariance = b.covariance.cast<double>();
  if (g.odometry_covariance != OdometryCovariance::kTracker || covariance.isZero(0.0) ||
      b.key.id != a.key.id + 1)
    return e;
  Matrix6d c = relative_pose_covariance(a.odom_pose, b.odom_pose, covariance) *
               (g.tracker_covariance_scale * g.tracker_covariance_scale);
  const double tt = g.tracker_translation_sigma_min;
  const double tr = g.tracker_rotation_sigma_min_deg * kDegToRad;
  c.diagonal() += Vector6d(tt * tt, tt * tt, tt * tt, tr * tr, tr * tr, tr * tr);
  if (c.allFinite() && c.llt().info() == Eigen::Success) e.covariance = c;
  return e;
}

PoseGraphEdge GraphOptimizer::loop_edge(const LoopEdge& loop, bool robust) {
  PoseGraphEdge e;
  e.relative = loop.relative;
  e.sigma = loop_sigma(loop);
  e.robust = robust;
  return e;
}

bool GraphOptimizer::consistent(const LoopEdge& loop, const Eigen::Isometry3d& from,
                                const Eigen::Isometry3d& to) const {
  const Eigen::Isometry3d error = loop.relative.inverse() * (from.inverse() * to);
  const Vector6d sigma = loop_sigma(loop);
  const double t = error.translation().norm() / sigma.head<3>().maxCoeff();
  const double r = Eigen::AngleAxisd(error.rotation()).angle() / sigma.tail<3>().maxCoeff();
  return std::max(t, r) <= config_.graph.loop_consistency_sigmas;
}

bool GraphOptimizer::held_by_loops(std::uint32_t node, const KeyframeGraph& graph,
                                   const GraphLoops& loops) const {
  const int needed = config_.graph.local_hold_loops;
  if (needed <= 0) return false;
  const KeyframeNode& n = graph.node(node);
  const auto& chain = graph.groups().at(n.stream).nodes;
  const auto at = chain.find(n.key.id);
  int held = 0;
  auto count = [&](std::uint32_t m) {
    const auto it = loops.at_node.find(m);
    if (it != loops.at_node.end()) held += static_cast<int>(it->second.size());
    return held >= needed;
  };
  if (count(at->second)) return true;
  auto back = at, on = at;
  for (int hop = 0; hop < config_.graph.local_hops; ++hop) {
    if (back != chain.begin() && count((--back)->second)) return true;
    if (std::next(on) != chain.end() && count((++on)->second)) return true;
  }
  return false;
}

LocalOptimization GraphOptimizer::optimize_local(KeyframeGraph& graph, GraphLoops& loops,
                                                 MapperStats& stats) const {
  LocalOptimization out;
  std::vector<std::uint32_t> pending;
  for (std::size_t i = 0; i < loops.size(); ++i)
    if (!loops.checked[i]) pending.push_back(static_cast<std::uint32_t>(i));
  if (pending.empty()) return out;
  const auto max_keyframes = static_cast<std::size_t>(config_.graph.local_max_keyframes);
  const StreamGroups& groups = graph.groups();

  // Free: each new loop's newer keyframe's stream, from its latest anchored keyframe before
  // it (or max_keyframes back) to the end (or max_keyframes on).
  NodeSet free(graph.size());
  for (std::uint32_t i : pending) {
    const KeyframeNode& b = graph.node(loops.nodes[i].second);
    const auto& chain = groups.at(b.stream).nodes;
    const auto at = chain.find(b.key.id);
    std::size_t count = 0;
    for (auto it = at;; --it) {
      free.insert(it->second);
      if ((it != at && graph.node(it->second).anchored) || it == chain.begin() ||
          ++count >= max_keyframes)
        break;
    }
    count = 0;
    for (auto it = std::next(at); it != chain.end() && count < max_keyframes; ++it, ++count)
      free.insert(it->second);
  }
  NodeSet stretches(0);
  if (config_.graph.local_max_free_keyframes > 0) stretches = free;
  // And the chains around both ends of each new loop, local_hops odometry edges deep: the
  // correction spreads on both sides. Not through checked loops: where a fleet has revisited a
  // place many times, every keyframe has loops and their hops would reach a region as large
  // as the map (the full pass spreads the correction further).
  // An older end held by local_hold_loops checked loops near it stays constant
  // (PoseGraphConfig::local_hold_loops): it and its neighbourhood are not freed.
  std::vector<std::uint32_t> frontier, held;
  for (std::uint32_t i : pending) {
    const std::uint32_t older = loops.nodes[i].first;
    if (free.count(older) || !held_by_loops(older, graph, loops))
      frontier.push_back(older);
    else
      held.push_back(older);
    frontier.push_back(loops.nodes[i].second);
  }
  NodeSet seen(graph.size());
  for (std::uint32_t n : frontier) seen.insert(n);
  for (int hop = 0; hop <= config_.graph.local_hops && !frontier.empty(); ++hop) {
    std::vector<std::uint32_t> next;
    for (std::uint32_t n : frontier) {
      if (free.size() >= 4 * max_keyframes) break;
      free.insert(n);
      if (hop == config_.graph.local_hops) continue;
      const KeyframeNode& node = graph.node(n);
      const auto& chain = groups.at(node.stream).nodes;
      const auto at = chain.find(node.key.id);
      auto visit = [&](std::uint32_t m) {
        if (seen.insert(m)) next.push_back(m);
      };
      if (at != chain.begin()) visit(std::prev(at)->second);
      if (std::next(at) != chain.end()) visit(std::next(at)->second);
    }
    frontier.swap(next);
  }

  // (Another loop's region may have freed a held end after all.)
  std::sort(held.begin(), held.end());
  held.erase(std::unique(held.begin(), held.end()), held.end());
  out.held_ends = static_cast<int>(
      std::count_if(held.begin(), held.end(), [&](std::uint32_t n) { return !free.count(n); }));

  // PoseGraphConfig::local_max_free_keyframes: only the keyframes nearest the new loops' ends
  // stay free; the rest of the region is held fixed (the full pass moves it later).
  const auto max_free = static_cast<std::size_t>(config_.graph.local_max_free_keyframes);
  NodeSet whole(0);
  if (max_free > 0 && free.size() > max_free) {
    std::vector<std::uint32_t> ends;
    for (std::uint32_t i : pending) ends.push_back(loops.nodes[i].second);
    for (std::uint32_t i : pending)
      if (free.count(loops.nodes[i].first)) ends.push_back(loops.nodes[i].first);
    whole = free;
    free = nearest_free(graph, whole, stretches, ends, max_free);
    out.bounded = static_cast<int>(whole.size() - free.size());
  }

  // The problem over a set of free nodes: them, then every node an edge ties them to, fixed.
  struct Region {
    LocalProblem problem;
    std::vector<PoseGraphEdge> edges;
    std::vector<std::uint32_t> used_loops;
    std::vector<Eigen::Isometry3d> start;
  };
  // The first keyframe of a group's anchor stream holds the group's frame (the map frame is
  // the first vehicle's first pose): a local solve that reaches it keeps it where it is, as
  // the full pass keeps its segment. Freed, it would drift with every solve that reaches the
  // anchor stream's start while other keyframes of the region hold the gauge.
  auto holds_frame = [&](std::uint32_t n) {
    const KeyframeNode& node = graph.node(n);
    if (groups.anchor_of(node.stream) != node.stream) return false;
    const auto& chain = groups.at(node.stream).nodes;
    return !chain.empty() && chain.begin()->second == n;
  };
  auto build = [&](NodeSet& free_set) {
    Region r;
    LocalProblem& problem = r.problem;
    std::vector<PoseGraphEdge>& edges = r.edges;
    const std::vector<std::uint32_t>& free_nodes = free_set.sorted();
    for (std::uint32_t n : free_nodes) problem.add(n, holds_frame(n));
    for (std::uint32_t n : free_nodes) {
      const KeyframeNode& node = graph.node(n);
      const auto& chain = groups.at(node.stream).nodes;
      const auto at = chain.find(node.key.id);
      if (at != chain.begin()) {
        const std::uint32_t p = std::prev(at)->second;
        if (!free_set.count(p)) {  // free predecessors add their edge as successors, below
          PoseGraphEdge e = odometry_edge(graph.node(p), node);
          e.from = problem.add(p, true);
          e.to = problem.index.at(n);
          edges.push_back(e);
        }
      }
      if (std::next(at) != chain.end()) {
        const std::uint32_t s = std::next(at)->second;
        PoseGraphEdge e = odometry_edge(node, graph.node(s));
        e.from = problem.index.at(n);
        e.to = problem.add(s, !free_set.count(s));
        edges.push_back(e);
      }
    }
    std::set<std::uint32_t> loop_ids(pending.begin(), pending.end());
    for (std::uint32_t n : free_nodes) {
      const auto it = loops.at_node.find(n);
      if (it != loops.at_node.end()) loop_ids.insert(it->second.begin(), it->second.end());
    }
    // Loops whose both ends are fixed add nothing.
    for (std::uint32_t i : loop_ids) {
      const auto [from, to] = loops.nodes[i];
      if (!free_set.count(from) && !free_set.count(to)) continue;
      r.used_loops.push_back(i);
      problem.add(from, !free_set.count(from));
      problem.add(to, !free_set.count(to));
    }
    // A region with no fixed node (a group's whole graph) keeps its anchor's first keyframe.
    if (std::find(problem.fixed.begin(), problem.fixed.end(), true) == problem.fixed.end()) {
      for (std::size_t k = 0; k < problem.nodes.size(); ++k) {
        const KeyframeNode& node = graph.node(problem.nodes[k]);
        const StreamGroups::Stream& anchor = groups.at(groups.anchor_of(node.stream));
        const auto first = anchor.nodes.begin();
        if (first != anchor.nodes.end() && first->second == problem.nodes[k])
          problem.fixed[k] = true;
      }
      // Not reached in a connected group (its anchor's first keyframe is in it); keep the
      // gauge fixed all the same.
      if (std::find(problem.fixed.begin(), problem.fixed.end(), true) == problem.fixed.end())
        problem.fixed[0] = true;
    }
    r.start.reserve(problem.nodes.size());
    for (std::uint32_t n : problem.nodes) r.start.push_back(graph.node(n).pose);
    return r;
  };

  auto solve = [&](const Region& region, std::vector<Eigen::Isometry3d>& poses) {
    std::vector<PoseGraphEdge> all = region.edges;
    for (std::uint32_t i : region.used_loops) {
      PoseGraphEdge e = loop_edge(loops.edges[i], loops.checked[i]);
      e.from = region.problem.index.at(loops.nodes[i].first);
      e.to = region.problem.index.at(loops.nodes[i].second);
      all.push_back(e);
    }
    out.loop_edges = static_cast<int>(region.used_loops.size());
    poses = region.start;
    return optimize_pose_graph(poses, region.problem.fixed, all, config_.graph);
  };
  auto inconsistent_loops = [&](const Region& region, const std::vector<Eigen::Isometry3d>& poses) {
    std::vector<std::uint32_t> inconsistent;
    for (std::uint32_t i : pending) {
      const auto [from, to] = loops.nodes[i];
      if (!consistent(loops.edges[i], poses[region.problem.index.at(from)],
                      poses[region.problem.index.at(to)]))
        inconsistent.push_back(i);
    }
    return inconsistent;
  };
  Region region = build(free);
  std::vector<Eigen::Isometry3d> poses;
  PoseGraphResult result = solve(region, poses);
  std::vector<std::uint32_t> inconsistent = inconsistent_loops(region, poses);
  // A bounded region that cannot accommodate a new loop may be too small for the drift it
  // corrects (PoseGraphConfig::local_widen_for_loops): the stretches of the whole region (runs
  // of a stream) that hold those loops' ends are freed whole and the problem solved again;
  // that decides.
  if (!inconsistent.empty() && out.bounded > 0 && config_.graph.local_widen_for_loops) {
    out.widened = true;
    for (std::uint32_t i : inconsistent)
      for (std::uint32_t end : {loops.nodes[i].first, loops.nodes[i].second}) {
        if (!whole.count(end)) continue;
        const KeyframeNode& node = graph.node(end);
        const auto& chain = groups.at(node.stream).nodes;
        const auto at = chain.find(node.key.id);
        free.insert(end);
        for (auto it = std::next(at); it != chain.end() && whole.count(it->second); ++it)
          free.insert(it->second);
        for (auto it = at; it != chain.begin() && whole.count(std::prev(it)->second);)
          free.insert((--it)->second);
      }
    out.bounded = static_cast<int>(whole.size() - free.size());
    region = build(free);
    result = solve(region, poses);
    inconsistent = inconsistent_loops(region, poses);
  }
  const LocalProblem& problem = region.problem;
  std::vector<std::uint32_t>& used_loops = region.used_loops;
  out.odometry_edges = static_cast<int>(region.edges.size());
  // New loops that the region cannot accommodate are dropped and the region solved again
  // without them, from the poses before.
  if (!inconsistent.empty()) {
    // Unchecked loops are the last ones: erasing them moves no checked loop's index.
    for (auto it = inconsistent.rbegin(); it != inconsistent.rend(); ++it) {
      const auto pos = static_cast<std::ptrdiff_t>(*it);
      loops.edges.erase(loops.edges.begin() + pos);
      loops.nodes.erase(loops.nodes.begin() + pos);
      loops.checked.erase(loops.checked.begin() + pos);
      --stats.verified;
      ++stats.rejected;
      ++stats.inconsistent;
    }
    out.dropped = static_cast<int>(inconsistent.size());
    // Renumber the loops used after the erased ones.
    std::vector<std::uint32_t> kept;
    for (std::uint32_t i : used_loops) {
      if (std::binary_search(inconsistent.begin(), inconsistent.end(), i)) continue;
      const auto shift =
          std::lower_bound(inconsistent.begin(), inconsistent.end(), i) - inconsistent.begin();
      kept.push_back(i - static_cast<std::uint32_t>(shift));
    }
    used_loops = kept;
    result = solve(region, poses);
  }
  if (result.diverged) ++stats.diverged;
  if (result.usable) {
    for (std::size_t k = 0; k < problem.nodes.size(); ++k)
      if (!problem.fixed[k]) graph.set_pose(problem.nodes[k], poses[k]);
  }
  loops.check_all(graph);
  out.ran = true;
  out.keyframes = static_cast<int>(problem.nodes.size());
  out.fixed = static_cast<int>(std::count(problem.fixed.begin(), problem.fixed.end(), true));
  out.free = out.keyframes - out.fixed;
  out.iterations = result.iterations;
  out.initial_cost = result.initial_cost;
  out.final_cost = result.final_cost;
  return out;
}

std::size_t full_pass_segment_keyframes(const PoseGraphConfig& config, std::size_t keyframes) {
  const auto base = static_cast<std::size_t>(config.segment_keyframes);
  if (config.full_pass_max_segments <= 0) return base;
  const auto most = static_cast<std::size_t>(config.full_pass_max_segments) * base;
  // The smallest multiple of segment_keyframes that cuts `keyframes` into at most
  // full_pass_max_segments segments (each stream's last one may be short).
  return base * std::max<std::size_t>(1, (keyframes + most - 1) / most);
}

FullPassProblem GraphOptimizer::full_pass_problem(const KeyframeGraph& graph,
                                                  const GraphLoops& loops, std::size_t pass) const {
  FullPassProblem p;
  p.config = config_.graph;
  const StreamGroups& groups = graph.groups();
  p.segment_keyframes = full_pass_segment_keyframes(config_.graph, graph.size());
  const std::size_t segment = p.segment_keyframes;
  // A stream's segments start at its first keyframe and then every segment keyframes from
  // the shift on.
  const std::size_t shift = config_.graph.full_pass_shift_segments ? pass % segment : 0;
  p.segment_of_node.assign(graph.size(), -1);
  p.anchor_of_stream.resize(groups.streams().size());
  p.last_segment_of_stream.assign(groups.streams().size(), -1);
  for (std::uint32_t s = 0; s < groups.streams().size(); ++s) {
    p.anchor_of_stream[s] = groups.anchor_of(s);
    const auto& chain = groups.at(s).nodes;
    std::size_t k = 0;
    std::int64_t previous = -1;
    for (const auto& [id, n] : chain) {
      const KeyframeNode& node = graph.node(n);
      const bool cut = k == 0 || (k + segment - shift) % segment == 0;
      ++k;
      if (cut) {
        p.poses.push_back(node.pose);
        // The anchor stream's first segment holds the group's frame.
        p.fixed.push_back(k == 1 && p.anchor_of_stream[s] == s);
        if (previous >= 0) {  // the odometry edge across the segment boundary
          const KeyframeNode& prev = graph.node(static_cast<std::uint32_t>(previous));
          const auto from =
              static_cast<std::size_t>(p.segment_of_node[static_cast<std::size_t>(previous)]);
          PoseGraphEdge e = odometry_edge(prev, node);
          e.from = static_cast<int>(from);
          e.to = static_cast<int>(p.poses.size() - 1);
          e.from_offset = p.poses[from].inverse() * prev.pose;
          p.edges.push_back(e);
        }
      }
      p.segment_of_node[n] = static_cast<std::int32_t>(p.poses.size() - 1);
      previous = n;
    }
    p.last_segment_of_stream[s] =
        chain.empty() ? -1 : static_cast<std::int32_t>(p.poses.size() - 1);
  }
  for (std::size_t i = 0; i < loops.size(); ++i) {
    if (!loops.checked[i]) continue;
    const auto [from, to] = loops.nodes[i];
    const std::int32_t a = p.segment_of_node[from], b = p.segment_of_node[to];
    if (a == b) continue;
    PoseGraphEdge e = loop_edge(loops.edges[i], true);
    e.from = a;
    e.to = b;
    e.from_offset = p.poses[static_cast<std::size_t>(a)].inverse() * graph.node(from).pose;
    e.to_offset = p.poses[static_cast<std::size_t>(b)].inverse() * graph.node(to).pose;
    p.edges.push_back(e);
    ++p.loop_edges;
  }
  // Every connected part needs a fixed segment: a group joined by a loop that was then dropped
  // as inconsistent stays joined without an edge between its parts.
  std::vector<std::size_t> parent(p.poses.size());
  for (std::size_t i = 0; i < parent.size(); ++i) parent[i] = i;
  auto root = [&](std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (const PoseGraphEdge& e : p.edges)
    parent[root(static_cast<std::size_t>(e.from))] = root(static_cast<std::size_t>(e.to));
  std::vector<bool> part_fixed(p.poses.size(), false);
  for (std::size_t i = 0; i < p.poses.size(); ++i)
    if (p.fixed[i]) part_fixed[root(i)] = true;
  for (std::size_t i = 0; i < p.poses.size(); ++i) {
    if (part_fixed[root(i)]) continue;
    p.fixed[i] = true;
    part_fixed[root(i)] = true;
  }
  p.before = p.poses;
  return p;
}

void GraphOptimizer::solve_full_pass(FullPassProblem& problem) {
  const auto start = std::chrono::steady_clock::now();
  const double cpu = thread_cpu_seconds();
  problem.result = optimize_pose_graph(problem.poses, problem.fixed, problem.edges, problem.config);
  problem.milliseconds = elapsed_ms(start);
  problem.cpu_s = thread_cpu_seconds() - cpu;
}

std::size_t GraphOptimizer::apply_full_pass(const FullPassProblem& problem, KeyframeGraph& graph,
                                            double min_shift, double min_turn) {
  if (!problem.result.usable) return 0;
  std::size_t moved = 0;
  std::vector<Eigen::Isometry3d> correction(problem.poses.size());
  for (std::size_t s = 0; s < problem.poses.size(); ++s)
    correction[s] = problem.poses[s] * problem.before[s].inverse();
  const StreamGroups& groups = graph.groups();
  for (std::uint32_t n = 0; n < graph.size(); ++n) {
    const KeyframeNode& node = graph.node(n);
    if (node.stream >= problem.anchor_of_stream.size() ||
        problem.anchor_of_stream[node.stream] != groups.anchor_of(node.stream))
      continue;
    const std::int32_t s = n < problem.segment_of_node.size()
                               ? problem.segment_of_node[n]
                               : problem.last_segment_of_stream[node.stream];
    if (s < 0) continue;
    const Eigen::Isometry3d pose = correction[static_cast<std::size_t>(s)] * node.pose;
    if ((pose.translation() - node.pose.translation()).norm() < min_shift &&
        Eigen::AngleAxisd(pose.linear() * node.pose.linear().transpose()).angle() < min_turn)
      continue;
    graph.set_pose(n, pose);
    ++moved;
  }
  return moved;
}

}  // namespace litamin2::mapping

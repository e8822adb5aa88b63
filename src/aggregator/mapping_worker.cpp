#include "litamin2/aggregator/mapping_worker.hpp"

#include "litamin2/core/stopwatch.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>

namespace litamin2::aggregator {
namespace {

constexpr std::chrono::milliseconds kPopTimeout(50);

std::chrono::steady_clock::duration seconds(double s) {
  return std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(s));
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

MappingWorker::MappingWorker(AggregatorCore& core, PatchQueue& queue, AggregatorSink& sink,
                             const AggregatorConfig& config)
    : core_(core), queue_(queue), sink_(sink), config_(config) {
  const mapping::Mapper& mapper = core_.mapper();
  status_.recovered = core_.recovered();
  status_.keyframes = mapper.stats().keyframes;
  status_.loops = mapper.loops().size();
  status_.optimizations = mapper.stats().optimizations;
  status_.merges = mapper.stats().merges;
  status_.tiles = core_.tiles().index().size();
  status_.map_pending = core_.map_pending();
  map_anchor_ = mapper.map_anchor();
  for (const auto& stream : mapper.graph().groups().streams()) {
    if (stream.nodes.empty()) continue;
    StreamCounts& c = status_.streams[stream.name];
    c.keyframes = stream.nodes.size();
    c.max_id = stream.nodes.rbegin()->first;
  }
  core_.take_moved();  // the recovered state is published whole by start()
}

MappingWorker::~MappingWorker() {
  stop();
}

void MappingWorker::start() {
  dirty_chunks_ = all_chunks(core_.mapper(), config_.publish.poses_chunk_keyframes);
  for (const auto& [key, summary] : core_.tiles().index()) dirty_tiles_.insert(key);
  publish(true, nullptr);
  thread_ = std::thread([this] { run(); });
}

void MappingWorker::stop() {
  queue_.close();
  if (thread_.joinable()) thread_.join();
}

void MappingWorker::run() {
  std::vector<Keyframe> batch;
  const std::size_t max_batch = static_cast<std::size_t>(config_.ingest.max_batch);
  for (;;) {
    TurnReport report;
    const double cpu = thread_cpu_seconds();
    const std::size_t n = queue_.pop_batch(batch, max_batch, kPopTimeout);
    if (n > 0 && !failed_) process(batch, report);
    batch.clear();
    if (n == 0 && queue_.closed() && queue_.size() == 0) break;
    // The poses this batch corrected go out before the tile work and the full pass (when the
    // poses period allows): a loop's correction does not wait behind the map.
    publish_poses_if_due(&report);
    if (!failed_) {
      update_map();
      report.full_pass = full_pass(false, &report);
    }
    publish(false, &report);
    report.cpu_s = thread_cpu_seconds() - cpu;
    if (observer_) observer_(report);
  }
  TurnReport report;
  const double cpu = thread_cpu_seconds();
  if (!failed_) {
    // What is left to fuse stays marked in the store (the map poses): a restart goes on.
    update_map(true);
    report.full_pass = full_pass(true, &report);
  }
  publish(true, &report);
  report.cpu_s = thread_cpu_seconds() - cpu;
  if (observer_) observer_(report);
}

bool MappingWorker::guarded(const char* what, const std::function<void()>& step) {
  busy_since_ = Clock::now().time_since_epoch().count();
  try {
    step();
  } catch (const std::exception& e) {
    // The store refused: stop ingesting; the process exits and, restarted, gets the patches
    // again from the writers' transient-local history.
    spdlog::error("{} failed: {}", what, e.what());
    failed_ = true;
    busy_since_ = 0;
    std::lock_guard lock(mutex_);
    status_.error = e.what();
    return false;
  }
  busy_since_ = 0;
  return true;
}

void MappingWorker::collect_moved() {
  const std::set<PoseChunk> chunks =
      chunks_of(core_.mapper(), core_.take_moved(), config_.publish.poses_chunk_keyframes);
  dirty_chunks_.insert(chunks.begin(), chunks.end());
}

bool MappingWorker::full_pass(bool stopping, TurnReport* report) {
  if (stopping) full_pass_worker_.wait();
  mapping::Mapper& mapper = core_.mapper();
  bool applied = false;
  auto apply = [&](const mapping::FullPassProblem& solved) {
    const auto a0 = Clock::now();
    if (!guarded("storing a full pass", [&] { core_.apply_full_pass(solved); })) return;
    // Its corrected poses go out now, so that the duty cycle counts their publication too,
    // with the mapping thread's copy and application (O(N) each).
    collect_moved();
    publish_poses(report);
    last_full_pass_end_ = Clock::now();
    last_full_pass_s_ = full_pass_copy_s_ + solved.milliseconds / 1000.0 + seconds_since(a0);
    if (solved.result.diverged) {
      spdlog::warn("full pass: {} segments: the solution ran off, refused", solved.poses.size());
    } else {
      // Debug: one runs every full_pass.min_interval_s while loops come in (19 lines in the
      // aggregator log of one demo run); their count is in the status and /metrics.
      spdlog::debug(
          "full pass: {} segments, {} loop edges, {} iterations, {:.1f} ms in the background",
          solved.poses.size(), solved.loop_edges, solved.result.iterations, solved.milliseconds);
    }
    applied = true;
    std::lock_guard lock(mutex_);
    ++status_.full_passes;
    status_.full_pass_cpu_s += solved.cpu_s;
  };
  if (auto solved = full_pass_worker_.take()) apply(*solved);
  if (failed_) return applied;
  if (stopping) {
    if (config_.full_pass.on_stop && mapper.loops_since_full_pass() > 0) {
      mapping::FullPassProblem problem = mapper.full_pass_problem();
      mapping::GraphOptimizer::solve_full_pass(problem);
      apply(problem);
    }
    return applied;
  }
  if (!full_pass_worker_.busy() &&
      full_pass_due(config_.full_pass, mapper.loops_since_full_pass(),
                    seconds_since(last_full_pass_end_), last_full_pass_s_)) {
    const auto c0 = Clock::now();
    full_pass_worker_.submit(mapper.full_pass_problem());
    full_pass_copy_s_ = seconds_since(c0);
  }
  return applied;
}

void MappingWorker::update_map(bool stopping) {
  const auto now = Clock::now();
  const bool persist = stopping || now >= next_map_persist_;
  if (core_.map_pending() == 0 && !(persist && core_.map_unsaved())) return;
  MapUpdate u;
  const auto max = static_cast<std::size_t>(config_.map_tiles.max_keyframes_per_turn);
  if (!guarded("storing the map tiles", [&] { u = core_.update_map(max, persist); })) return;
  if (persist) next_map_persist_ = now + seconds(config_.map_tiles.persist_period_s);
  dirty_tiles_.insert(u.tiles.begin(), u.tiles.end());
  if (!u.tiles.empty()) summary_dirty_ = true;
  std::lock_guard lock(mutex_);
  status_.tiles = core_.tiles().index().size();
  status_.map_pending = core_.map_pending();
  status_.ingest_cpu = core_.cpu();
}

void MappingWorker::process(std::vector<Keyframe>& batch, TurnReport& report) {
  const auto start = Clock::now();
  IngestResult r;
  if (!guarded("ingest", [&] { r = core_.ingest(batch); })) return;
  const mapping::Mapper& mapper = core_.mapper();
  report.added = r.added;
  report.new_loops = r.new_loops;
  report.optimization = r.optimization;
  if (r.optimization.ran) {
    spdlog::debug("optimised: {} keyframes, {} loop edges, cost {:.4g} -> {:.4g}, {:.1f} ms",
                  r.optimization.keyframes, r.optimization.loop_edges, r.optimization.initial_cost,
                  r.optimization.final_cost, r.optimization.milliseconds);
  }
  if (r.new_loops > 0) {
    spdlog::debug("{} new loop edge(s)", r.new_loops);
    loop_batches_.push_back(start);
  }
  collect_moved();
  if (r.added > 0) summary_dirty_ = true;
  const std::string anchor = mapper.map_anchor();
  if (anchor != map_anchor_) {
    // A stream with earlier data arrived (streams starting together): the map frame is now
    // another group's, which changes every stream's frame; tell them at once.
    if (!map_anchor_.empty())
      spdlog::info("map frame: now stream {}'s (was {}'s)", anchor, map_anchor_);
    map_anchor_ = anchor;
    const std::set<PoseChunk> all = all_chunks(mapper, config_.publish.poses_chunk_keyframes);
    dirty_chunks_.insert(all.begin(), all.end());
    poses_now_ = true;
  }

  std::lock_guard lock(mutex_);
  status_.keyframes = mapper.stats().keyframes;
  status_.duplicates = core_.duplicates();
  status_.loops = mapper.loops().size();
  status_.optimizations = mapper.stats().optimizations;
  status_.merges = mapper.stats().merges;
  ++status_.batches;
  status_.ingest_cpu = core_.cpu();
  status_.mapper_cpu = mapper.cpu();
  status_.map_pending = core_.map_pending();
  status_.last_store_ms = r.store_ms;
  status_.last_mapper_ms = r.mapper_ms;
  if (r.optimization.ran) {
    status_.last_optimize_ms = r.optimization.milliseconds;
    status_.optimize_seconds.observe(r.optimization.milliseconds * 1e-3);
  }
  for (const KeyframeKey& key : r.keys) {
    StreamCounts& c = status_.streams[key.stream];
    ++c.keyframes;
    c.max_id = std::max(c.max_id, key.id);
  }
}

void MappingWorker::publish_poses(TurnReport* report) {
  if (dirty_chunks_.empty()) return;
  poses_now_ = false;
  const double t = thread_cpu_seconds();
  const auto chunk_keyframes = static_cast<std::uint64_t>(config_.publish.poses_chunk_keyframes);
  for (const PoseChunk& chunk : dirty_chunks_)
    sink_.publish_poses(chunk_poses(core_.mapper(), chunk, chunk_keyframes));
  dirty_chunks_.clear();
  const auto now = Clock::now();
  for (const Clock::time_point& start : loop_batches_) {
    const double ms = std::chrono::duration<double, std::milli>(now - start).count();
    if (report) report->loop_latency_ms.push_back(ms);
  }
  loop_batches_.clear();
  next_poses_ = now + seconds(config_.publish.poses_period_s);
  std::lock_guard lock(mutex_);
  status_.poses_cpu_s += thread_cpu_seconds() - t;
}

void MappingWorker::publish_poses_if_due(TurnReport* report) {
  if (!dirty_chunks_.empty() && (poses_now_ || Clock::now() >= next_poses_)) publish_poses(report);
}

void MappingWorker::publish(bool force, TurnReport* report) {
  const auto now = Clock::now();
  if (!dirty_chunks_.empty() && (force || poses_now_ || now >= next_poses_)) publish_poses(report);
  if (!dirty_tiles_.empty() && (force || now >= next_tiles_)) {
    const double t = thread_cpu_seconds();
    for (const mapping::TileKey& key : dirty_tiles_)
      sink_.publish_tile(tile_output(core_.mapper(), core_.tiles(), key));
    const std::size_t published = dirty_tiles_.size();
    dirty_tiles_.clear();
    next_tiles_ = now + seconds(config_.publish.tiles_period_s);
    std::lock_guard lock(mutex_);
    status_.tiles_published += published;
    status_.tiles_cpu_s += thread_cpu_seconds() - t;
  }
  if (summary_dirty_ && (force || now >= next_summary_)) {
    const double t = thread_cpu_seconds();
    sink_.publish_summary(map_summary(core_.mapper(), core_.tiles(),
                                      static_cast<std::size_t>(config_.publish.summary_max_means)));
    summary_dirty_ = false;
    next_summary_ = now + seconds(config_.publish.summary_period_s);
    std::lock_guard lock(mutex_);
    status_.summary_cpu_s += thread_cpu_seconds() - t;
  }
}

WorkerStatus MappingWorker::status() const {
  std::lock_guard lock(mutex_);
  return status_;
}

bool MappingWorker::healthy(std::chrono::duration<double> stall_timeout,
                            Clock::time_point now) const {
  if (failed_) return false;
  const Clock::rep since = busy_since_;
  if (since == 0) return true;
  return now - Clock::time_point(Clock::duration(since)) < stall_timeout;
}

}  // namespace litamin2::aggregator

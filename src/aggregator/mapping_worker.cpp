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

}  // namespace

MappingWorker::MappingWorker(AggregatorCore& core, PatchQueue& queue, AggregatorSink& sink,
                             const AggregatorConfig& config)
    : core_(core), queue_(queue), sink_(sink), config_(config) {
  const mapping::Mapper& mapper = core_.mapper();
  status_.recovered = core_.recovered();
  status_.keyframes = mapper.stats().keyframes;
  status_.loops = mapper.loops().size();
  status_.optimizations = mapper.stats().optimizations;
  map_anchor_ = mapper.map_anchor();
  for (const mapping::KeyframePose& p : mapper.poses()) {
    StreamCounts& c = status_.streams[p.key.stream];
    ++c.keyframes;
    c.max_id = std::max(c.max_id, p.key.id);
  }
}

MappingWorker::~MappingWorker() {
  stop();
}

void MappingWorker::start() {
  for (const StreamPoses& s : all_stream_poses(core_.mapper())) sink_.publish_poses(s);
  publish(true);
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
    const std::size_t n = queue_.pop_batch(batch, max_batch, kPopTimeout);
    if (n > 0 && !failed_) process(batch);
    batch.clear();
    if (n == 0 && queue_.closed() && queue_.size() == 0) break;
    if (!failed_) full_pass(false);
    publish(false);
  }
  if (!failed_) full_pass(true);
  publish(true);
}

void MappingWorker::full_pass(bool stopping) {
  if (stopping) full_pass_worker_.wait();
  mapping::Mapper& mapper = core_.mapper();
  auto apply = [&](const mapping::FullPassProblem& solved) {
    const auto a0 = Clock::now();
    busy_since_ = a0.time_since_epoch().count();
    try {
      core_.apply_full_pass(solved);
    } catch (const std::exception& e) {
      spdlog::error("storing a full pass failed: {}", e.what());
      failed_ = true;
      busy_since_ = 0;
      std::lock_guard lock(mutex_);
      status_.error = e.what();
      return;
    }
    busy_since_ = 0;
    last_full_pass_end_ = Clock::now();
    // The duty cycle counts the mapping thread's copy and application (O(N) each) too.
    last_full_pass_s_ = full_pass_copy_s_ + solved.milliseconds / 1000.0 +
                        std::chrono::duration<double>(last_full_pass_end_ - a0).count();
    spdlog::info(
        "full pass: {} segments, {} loop edges, {} iterations, {:.1f} ms in the background",
        solved.poses.size(), solved.loop_edges, solved.result.iterations, solved.milliseconds);
    for (const auto& [stream, counts] : status().streams) dirty_streams_.insert(stream);
    summary_dirty_ = true;
    std::lock_guard lock(mutex_);
    ++status_.full_passes;
    status_.full_pass_cpu_s += solved.cpu_s;
  };
  if (auto solved = full_pass_worker_.take()) apply(*solved);
  if (failed_) return;
  if (stopping) {
    if (config_.full_pass.on_stop && mapper.loops_since_full_pass() > 0) {
      mapping::FullPassProblem problem = mapper.full_pass_problem();
      mapping::GraphOptimizer::solve_full_pass(problem);
      apply(problem);
    }
    return;
  }
  const double since = std::chrono::duration<double>(Clock::now() - last_full_pass_end_).count();
  if (!full_pass_worker_.busy() &&
      full_pass_due(config_.full_pass, mapper.loops_since_full_pass(), since, last_full_pass_s_)) {
    const auto c0 = Clock::now();
    full_pass_worker_.submit(mapper.full_pass_problem());
    full_pass_copy_s_ = std::chrono::duration<double>(Clock::now() - c0).count();
  }
}

void MappingWorker::process(std::vector<Keyframe>& batch) {
  const auto start = Clock::now();
  busy_since_ = start.time_since_epoch().count();
  IngestResult r;
  try {
    r = core_.ingest(batch);
  } catch (const std::exception& e) {
    // The store refused the batch: nothing of it reached the mapper. Stop ingesting; the
    // process exits and, restarted, gets the patches again from the writers' transient-local
    // history.
    spdlog::error("ingest failed: {}", e.what());
    failed_ = true;
    busy_since_ = 0;
    std::lock_guard lock(mutex_);
    status_.error = e.what();
    return;
  }
  busy_since_ = 0;
  const mapping::Mapper& mapper = core_.mapper();
  // An optimisation, or the map frame moving to another group, changes every stream's poses.
  bool all_changed = r.optimization.ran;
  if (r.optimization.ran) {
    spdlog::info("optimised: {} keyframes, {} loop edges, cost {:.4g} -> {:.4g}, {:.1f} ms",
                 r.optimization.keyframes, r.optimization.loop_edges, r.optimization.initial_cost,
                 r.optimization.final_cost, r.optimization.milliseconds);
  }
  if (r.new_loops > 0) spdlog::info("{} new loop edge(s)", r.new_loops);
  dirty_streams_.insert(r.streams.begin(), r.streams.end());
  if (r.added > 0) summary_dirty_ = true;
  const std::string anchor = mapper.map_anchor();
  if (anchor != map_anchor_) {
    // A stream with earlier data arrived (streams starting together): the map frame is now
    // another group's, which changes every stream's frame; tell them at once.
    if (!map_anchor_.empty())
      spdlog::info("map frame: now stream {}'s (was {}'s)", anchor, map_anchor_);
    map_anchor_ = anchor;
    all_changed = true;
    poses_now_ = true;
  }
  if (all_changed) {
    for (const auto& [stream, counts] : status().streams) dirty_streams_.insert(stream);
  }

  std::lock_guard lock(mutex_);
  status_.keyframes = mapper.stats().keyframes;
  status_.duplicates = core_.duplicates();
  status_.loops = mapper.loops().size();
  status_.optimizations = mapper.stats().optimizations;
  ++status_.batches;
  status_.ingest_cpu = core_.cpu();
  status_.mapper_cpu = mapper.cpu();
  status_.last_store_ms = r.store_ms;
  status_.last_mapper_ms = r.mapper_ms;
  if (r.optimization.ran) status_.last_optimize_ms = r.optimization.milliseconds;
  for (const KeyframeKey& key : r.keys) {
    StreamCounts& c = status_.streams[key.stream];
    ++c.keyframes;
    c.max_id = std::max(c.max_id, key.id);
  }
}

void MappingWorker::publish(bool force) {
  const auto now = Clock::now();
  if (!dirty_streams_.empty() && (force || poses_now_ || now >= next_poses_)) {
    poses_now_ = false;
    const double t = thread_cpu_seconds();
    const std::vector<std::string> streams(dirty_streams_.begin(), dirty_streams_.end());
    for (const StreamPoses& s : stream_poses(core_.mapper(), streams)) sink_.publish_poses(s);
    dirty_streams_.clear();
    next_poses_ = now + seconds(config_.publish.poses_period_s);
    std::lock_guard lock(mutex_);
    status_.poses_cpu_s += thread_cpu_seconds() - t;
  }
  if (summary_dirty_ && (force || now >= next_summary_)) {
    const double t = thread_cpu_seconds();
    const std::vector<Distribution> map = core_.mapper().global_map();
    sink_.publish_summary(map_summary(core_.mapper(), map,
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

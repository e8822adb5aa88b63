#pragma once
/// The aggregator's mapping thread. Each turn: takes a batch of keyframes off the PatchQueue
/// and ingests it (store commit, then mapper); publishes the corrected poses (when the poses
/// period allows) before any map work, so that a loop's correction does not wait behind the
/// tiles; fuses at most map_tiles.max_keyframes_per_turn
/// of the keyframes that arrived or moved into the map tiles (and commits them, at most every
/// map_tiles.persist_period_s and at stop); applies a
/// solved background full pass and starts the next when due; publishes, each at most at its
/// period, the corrected poses of the pose chunks holding a keyframe that was added or moved,
/// the tiles that changed and the map summary (from the tile index). Every step costs what
/// changed, not the map. Owns nothing but the thread: the core, queue and sink are the
/// caller's.

#include "litamin2/aggregator/aggregator_config.hpp"
#include "litamin2/aggregator/aggregator_core.hpp"
#include "litamin2/aggregator/aggregator_sink.hpp"
#include "litamin2/aggregator/full_pass_worker.hpp"
#include "litamin2/aggregator/patch_queue.hpp"

#include "litamin2/service/histogram.hpp"

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <vector>

namespace litamin2::aggregator {

/// One stream as the status reports it.
struct StreamCounts {
  std::size_t keyframes = 0;
  /// Highest keyframe id received; missing = max_id + 1 - keyframes (gaps, late patches).
  std::uint64_t max_id = 0;
};

/// A consistent snapshot of the mapping thread's counters.
struct WorkerStatus {
  std::size_t keyframes = 0;
  std::size_t recovered = 0;
  std::size_t duplicates = 0;
  std::size_t loops = 0;
  /// Merges of two streams' groups confirmed (mapping::MapperStats::merges).
  std::size_t merges = 0;
  std::size_t optimizations = 0;
  std::size_t batches = 0;
  double last_store_ms = 0.0;
  double last_mapper_ms = 0.0;
  double last_optimize_ms = 0.0;
  /// Every local optimisation's wall time since the start, seconds (the Prometheus histogram).
  service::Histogram optimize_seconds{service::latency_buckets_seconds()};
  std::map<std::string, StreamCounts> streams;
  /// CPU time of the mapping thread by stage, seconds: ingest (store, mapper, map tiles) ...
  IngestCpu ingest_cpu;
  mapping::MapperCpu mapper_cpu;
  /// ... building and publishing the corrected poses ...
  double poses_cpu_s = 0.0;
  /// ... the map summary and the tiles.
  double summary_cpu_s = 0.0;
  double tiles_cpu_s = 0.0;
  /// Map tiles, keyframes waiting to be fused into them, tiles published.
  std::size_t tiles = 0;
  std::size_t map_pending = 0;
  std::size_t tiles_published = 0;
  /// Full passes applied, and the background thread's CPU time solving them, seconds.
  std::size_t full_passes = 0;
  double full_pass_cpu_s = 0.0;
  /// The store failed (disk full, I/O error): the process must exit and be restarted.
  std::string error;
};

/// What one turn of the mapping thread did (for benchmarks and tests; MappingWorker::observe).
struct TurnReport {
  /// Keyframes new to the mapper, and loops found, in this turn's batch.
  std::size_t added = 0;
  std::size_t new_loops = 0;
  /// The thread's CPU time in this turn (ingest, map tiles, full pass, publication), seconds.
  double cpu_s = 0.0;
  /// From the start of the ingest of each earlier batch with new loops to the publication of
  /// the corrected poses it caused, completed in this turn, milliseconds.
  std::vector<double> loop_latency_ms;
  /// The local optimisation after this turn's loops (Mapper::optimize): ran, its free and
  /// fixed keyframes and loop edges.
  mapping::OptimizeSummary optimization;
  /// A full pass was applied in this turn.
  bool full_pass = false;
};

class MappingWorker {
 public:
  using Clock = std::chrono::steady_clock;
  using Observer = std::function<void(const TurnReport&)>;

  MappingWorker(AggregatorCore& core, PatchQueue& queue, AggregatorSink& sink,
                const AggregatorConfig& config);
  /// Stops (see stop()) and joins.
  ~MappingWorker();
  MappingWorker(const MappingWorker&) = delete;
  MappingWorker& operator=(const MappingWorker&) = delete;

  /// Called on the mapping thread after every turn that did something. Set before start().
  void observe(Observer observer) { observer_ = std::move(observer); }
  /// Publishes every pose chunk and tile once (the recovered state), then starts the thread.
  void start();
  /// Closes the queue, ingests what is left in it, publishes pending outputs and joins.
  void stop();

  WorkerStatus status() const;
  /// No batch has been in processing for longer than `stall_timeout` and the store works.
  bool healthy(std::chrono::duration<double> stall_timeout,
               Clock::time_point now = Clock::now()) const;
  bool failed() const { return failed_; }

 private:
  void run();
  void process(std::vector<Keyframe>& batch, TurnReport& report);
  /// Fuses into the tiles; stores them when map_tiles.persist_period_s has passed, or when
  /// `stopping`.
  void update_map(bool stopping = false);
  /// Publishes what is due; `force`: all that is pending, now.
  void publish(bool force, TurnReport* report);
  void publish_poses(TurnReport* report);
  /// Publishes the dirty pose chunks if the poses period has elapsed (or the map frame moved).
  void publish_poses_if_due(TurnReport* report);
  /// Applies a solved full pass and starts the next when due (full_pass_due); at `stopping`,
  /// waits for the one in flight and runs a last one if configured. True if one was applied.
  bool full_pass(bool stopping, TurnReport* report);
  /// Runs `step` (a store write); on failure logs, records the error and stops ingesting.
  bool guarded(const char* what, const std::function<void()>& step);
  /// Marks the chunks of the nodes added or moved since the last call for publication.
  void collect_moved();

  AggregatorCore& core_;
  PatchQueue& queue_;
  AggregatorSink& sink_;
  const AggregatorConfig& config_;
  Observer observer_;
  std::thread thread_;
  std::atomic<bool> failed_{false};
  /// Start of the batch in processing (epoch = none), for the watchdog.
  std::atomic<Clock::rep> busy_since_{0};

  // Mapping thread only.
  std::set<PoseChunk> dirty_chunks_;
  std::set<mapping::TileKey> dirty_tiles_;
  /// Ingest starts of the batches with new loops whose poses are not published yet.
  std::vector<Clock::time_point> loop_batches_;
  /// The map frame's anchor stream (Mapper::map_anchor) after the last batch.
  std::string map_anchor_;
  /// Publish the dirty chunks without waiting for the period (the map frame moved).
  bool poses_now_ = false;
  bool summary_dirty_ = true;
  Clock::time_point next_poses_{};
  Clock::time_point next_summary_{};
  Clock::time_point next_tiles_{};
  Clock::time_point next_map_persist_{};

  FullPassWorker full_pass_worker_;
  Clock::time_point last_full_pass_end_ = Clock::now();
  double last_full_pass_s_ = 0.0;
  double full_pass_copy_s_ = 0.0;

  mutable std::mutex mutex_;
  WorkerStatus status_;
};

}  // namespace litamin2::aggregator

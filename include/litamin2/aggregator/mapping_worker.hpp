#pragma once
/// The aggregator's mapping thread: takes batches of keyframes off the PatchQueue, ingests them
/// (store commit, then mapper), and publishes the corrected poses of the streams that changed
/// (all streams after an optimisation) and the map summary, each at most at its configured
/// period. Owns nothing but the thread: the core, queue and sink are the caller's.

#include "litamin2/aggregator/aggregator_config.hpp"
#include "litamin2/aggregator/aggregator_core.hpp"
#include "litamin2/aggregator/aggregator_sink.hpp"
#include "litamin2/aggregator/full_pass_worker.hpp"
#include "litamin2/aggregator/patch_queue.hpp"

#include <atomic>
#include <chrono>
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <thread>

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
  std::size_t optimizations = 0;
  std::size_t batches = 0;
  double last_store_ms = 0.0;
  double last_mapper_ms = 0.0;
  double last_optimize_ms = 0.0;
  std::map<std::string, StreamCounts> streams;
  /// CPU time of the mapping thread by stage, seconds: ingest (store, mapper) ...
  IngestCpu ingest_cpu;
  mapping::MapperCpu mapper_cpu;
  /// ... building and publishing the corrected poses ...
  double poses_cpu_s = 0.0;
  /// ... building (the global map) and publishing the map summary.
  double summary_cpu_s = 0.0;
  /// Full passes applied, and the background thread's CPU time solving them, seconds.
  std::size_t full_passes = 0;
  double full_pass_cpu_s = 0.0;
  /// The store failed failed (disk full, I/O error): the process must exit and be restarted.
  std::string error;
};

class MappingWorker {
 public:
  using Clock = std::chrono::steady_clock;

  MappingWorker(AggregatorCore& core, PatchQueue& queue, AggregatorSink& sink,
                const AggregatorConfig& config);
  /// Stops (see stop()) and joins.
  ~MappingWorker();
  MappingWorker(const MappingWorker&) = delete;
  MappingWorker& operator=(const MappingWorker&) = delete;

  /// Publishes every stream's poses once (the recovered state), then starts the thread.
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
  void process(std::vector<Keyframe>& batch);
  void publish(bool force);
  /// Applies a solved full pass and starts the next when due (full_pass_due); at `stopping`,
  /// waits for the one in flight and runs a last one if configured.
  void full_pass(bool stopping);

  AggregatorCore& core_;
  PatchQueue& queue_;
  AggregatorSink& sink_;
  const AggregatorConfig& config_;
  std::thread thread_;
  std::atomic<bool> failed_{false};
  /// Start of the batch in processing (epoch = none), for the watchdog.
  std::atomic<Clock::rep> busy_since_{0};

  // Mapping thread only.
  std::set<std::string> dirty_streams_;
  /// The map frame's anchor stream (Mapper::map_anchor) after the last batch.
  std::string map_anchor_;
  /// Publish the dirty streams' poses without waiting for the period (the map frame moved).
  bool poses_now_ = false;
  bool summary_dirty_ = true;
  Clock::time_point next_poses_{};
  Clock::time_point next_summary_{};

  FullPassWorker full_pass_worker_;
  Clock::time_point last_full_pass_end_ = Clock::now();
  double last_full_pass_s_ = 0.0;
  double full_pass_copy_s_ = 0.0;

  mutable std::mutex mutex_;
  WorkerStatus status_;
};

}  // namespace litamin2::aggregator

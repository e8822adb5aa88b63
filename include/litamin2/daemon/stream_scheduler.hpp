#pragma once
/// Runs the frames of many sensor streams on `threads` worker threads of its own: each
/// stream's frames are processed in arrival order, one at a time (a stream has at most one task
/// in flight, which re-schedules itself at the back of the ready queue while its queue is not
/// empty, so streams take turns); different streams run in parallel. An idle worker sleeps on a
/// condition variable: oneTBB's workers, which ran the frames before, spin and yield for a while
/// after every task, which on one daemon core was ~7 % of the daemon's CPU (docs/benchmarks.md,
/// "Streams per daemon core"). A frame runs inside a oneTBB arena whose slots are all the
/// workers' own (no oneTBB worker threads): a frame's nested parallel_for is shared with the
/// other workers that are busy with frames (they steal its tasks while they wait in their own),
/// and runs on its own thread when they are idle. The workers' scheduling class and CPUs are
/// opt-in (worker_scheduling.hpp).

#include "litamin2/daemon/frame.hpp"
#include "litamin2/daemon/stream_queue.hpp"
#include "litamin2/daemon/worker_scheduling.hpp"

#include <tbb/task_arena.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <shared_mutex>
#include <string>
#include <thread>
#include <vector>

namespace litamin2::daemon {

/// Counters of one stream, as seen by the scheduler.
struct SchedulerCounters {
  /// Frames accepted by submit().
  std::uint64_t submitted = 0;
  /// Frames whose processor returned normally.
  std::uint64_t processed = 0;
  /// Frames whose processor threw.
  std::uint64_t failed = 0;
  /// Frames dropped: the oldest when the queue was full, and queued frames at shutdown.
  std::uint64_t dropped = 0;
  /// Frames waiting now.
  std::size_t queued = 0;
};

/// What drain() did.
struct DrainResult {
  /// Every accepted frame was processed or dropped and no task is running.
  bool complete = false;
  /// Frames still queued at the deadline, dropped.
  std::size_t dropped = 0;
  /// Frames still being processed when drain() returned (only if !complete).
  std::size_t in_flight = 0;
};

class StreamScheduler {
 public:
  /// Called on a worker thread with each frame of a stream, in order, never concurrently for
  /// one stream. Exceptions are caught, counted and reported to the error handler.
  using Processor = std::function<void(Frame&)>;
  /// Told about a processor's exception: stream id and what().
  using ErrorHandler = std::function<void(const std::string&, const std::string&)>;
  /// Identifies a stream in submit() and counters().
  using Handle = std::size_t;

  /// `threads` workers (0 = one per core); `queue_depth` frames per stream (>= 1); each worker
  /// gets `scheduling` before any frame runs. Throws std::runtime_error (with the workers
  /// stopped) when the scheduling cannot be applied, e.g. a real-time policy without
  /// CAP_SYS_NICE.
  StreamScheduler(int threads, std::size_t queue_depth, WorkerScheduling scheduling = {});
  /// Drops queued frames and waits for frames in processing.
  ~StreamScheduler();

  StreamScheduler(const StreamScheduler&) = delete;
  StreamScheduler& operator=(const StreamScheduler&) = delete;

  /// Adds a stream; thread-safe, also while frames are being processed.
  Handle add_stream(std::string id, Processor processor);
  /// Queues a frame of the stream and schedules the stream if it is idle. Never blocks (beyond
  /// short locks); if the stream's queue is full, its oldest frame is dropped and counted.
  /// Returns false (and discards the frame) once drain() has started.
  bool submit(Handle stream, Frame frame);

  /// Stops taking input, then waits up to `timeout` for queued frames to be processed; frames
  /// still queued at the deadline are dropped; waits up to `grace` more for frames in
  /// processing. Idempotent.
  DrainResult drain(std::chrono::milliseconds timeout,
                    std::chrono::milliseconds grace = std::chrono::milliseconds(500));

  void set_error_handler(ErrorHandler handler);

  int threads() const { return threads_; }
  std::size_t queue_depth() const { return queue_depth_; }
  const WorkerScheduling& scheduling() const { return scheduling_; }
  std::size_t stream_count() const;
  const std::string& stream_id(Handle stream) const;
  SchedulerCounters counters(Handle stream) const;
  /// Frames being processed now, over all streams.
  std::size_t in_flight() const;
  /// How long the frame that has been in processing longest has been so (zero if none): a
  /// frame stuck for long means the daemon is wedged.
  std::chrono::steady_clock::duration longest_in_flight(
      std::chrono::steady_clock::time_point now = std::chrono::steady_clock::now()) const;

 private:
  struct Stream;

  Stream& stream(Handle handle) const;
  void schedule(Stream& stream);
  /// A worker thread: runs ready streams' frames until stop_workers().
  void work();
  void stop_workers();
  void run(Stream& stream);
  void finish_task();
  std::size_t clear_queues();

  int threads_;
  std::size_t queue_depth_;
  WorkerScheduling scheduling_;
  tbb::task_arena arena_;

  /// Streams with a task to run, in the order they were scheduled.
  std::mutex ready_mutex_;
  std::condition_variable ready_cv_;
  std::deque<Stream*> ready_;
  bool stopping_ = false;
  std::vector<std::thread> workers_;

  mutable std::shared_mutex streams_mutex_;
  std::vector<std::unique_ptr<Stream>> streams_;
  /// Shared by submit(), exclusive while drain() stops input.
  std::shared_mutex input_mutex_;
  bool accepting_ = true;

  mutable std::mutex tasks_mutex_;
  std::condition_variable tasks_done_;
  std::size_t active_tasks_ = 0;

  std::mutex error_mutex_;
  ErrorHandler on_error_;
};

}  // namespace litamin2::daemon

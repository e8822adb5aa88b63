#include "litamin2/daemon/stream_scheduler.hpp"

#include <pthread.h>
#include <tbb/info.h>

#include <algorithm>
#include <stdexcept>

namespace litamin2::daemon {

struct StreamScheduler::Stream {
  Stream(std::string id_, Processor processor_, std::size_t depth)
      : id(std::move(id_)), processor(std::move(processor_)), queue(depth) {}

  const std::string id;
  const Processor processor;
  StreamQueue<Frame> queue;
  /// A task of this stream is queued in the arena or running.
  std::atomic<bool> scheduled{false};
  /// steady_clock nanoseconds since epoch when the running frame started; 0 when idle.
  std::atomic<std::int64_t> busy_since{0};
  std::atomic<std::uint64_t> processed{0};
  std::atomic<std::uint64_t> failed{0};
};

namespace {
std::int64_t to_ns(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(t.time_since_epoch()).count();
}
}  // namespace

StreamScheduler::StreamScheduler(int threads, std::size_t queue_depth, WorkerScheduling scheduling)
    : threads_(threads > 0 ? threads : tbb::info::default_concurrency()),
      queue_depth_(queue_depth),
      scheduling_(std::move(scheduling)) {
  if (queue_depth_ == 0) throw std::invalid_argument("StreamScheduler: queue depth must be >= 1");
  // Every slot is reserved for the workers below, which join the arena for each frame: oneTBB
  // starts no worker threads for it.
  arena_.initialize(threads_, static_cast<unsigned>(threads_));
  workers_.reserve(static_cast<std::size_t>(threads_));
  try {
    // No stream exists yet, so no frame runs before its worker's scheduling is set.
    for (int i = 0; i < threads_; ++i) {
      workers_.emplace_back([this] { work(); });
      apply_worker_scheduling(workers_.back().native_handle(), scheduling_);
    }
  } catch (...) {
    stop_workers();
    throw;
  }
}

StreamScheduler::~StreamScheduler() {
  drain(std::chrono::milliseconds(0), std::chrono::milliseconds(0));
  {
    std::unique_lock lock(tasks_mutex_);
    tasks_done_.wait(lock, [&] { return active_tasks_ == 0; });
  }
  stop_workers();
}

void StreamScheduler::stop_workers() {
  {
    std::lock_guard lock(ready_mutex_);
    stopping_ = true;
  }
  ready_cv_.notify_all();
  for (std::thread& worker : workers_)
    if (worker.joinable()) worker.join();
}

void StreamScheduler::work() {
  // Named so that per-thread CPU (top -H, /proc/PID/task) tells the workers from Fast DDS's
  // threads (tests/integration/daemon_bench.sh splits the daemon's CPU by it).
  pthread_setname_np(pthread_self(), "stream-worker");
  for (;;) {
    Stream* s = nullptr;
    {
      std::unique_lock lock(ready_mutex_);
      ready_cv_.wait(lock, [&] { return stopping_ || !ready_.empty(); });
      if (ready_.empty()) return;  // stopping, and nothing left to run
      s = ready_.front();
      ready_.pop_front();
    }
    arena_.execute([&] { run(*s); });
  }
}

StreamScheduler::Handle StreamScheduler::add_stream(std::string id, Processor processor) {
  if (!processor) throw std::invalid_argument("StreamScheduler: empty processor");
  std::unique_lock lock(streams_mutex_);
  streams_.push_back(std::make_unique<Stream>(std::move(id), std::move(processor), queue_depth_));
  return streams_.size() - 1;
}

StreamScheduler::Stream& StreamScheduler::stream(Handle handle) const {
  std::shared_lock lock(streams_mutex_);
  if (handle >= streams_.size()) throw std::out_of_range("StreamScheduler: unknown stream");
  return *streams_[handle];
}

bool StreamScheduler::submit(Handle handle, Frame frame) {
  Stream& s = stream(handle);
  std::shared_lock input(input_mutex_);
  if (!accepting_) return false;
  s.queue.push(std::move(frame));
  if (!s.scheduled.exchange(true)) schedule(s);
  return true;
}

void StreamScheduler::schedule(Stream& s) {
  {
    std::lock_guard lock(tasks_mutex_);
    ++active_tasks_;
  }
  {
    std::lock_guard lock(ready_mutex_);
    ready_.push_back(&s);
  }
  ready_cv_.notify_one();
}

void StreamScheduler::run(Stream& s) {
  if (std::optional<Frame> frame = s.queue.pop()) {
    s.busy_since.store(to_ns(std::chrono::steady_clock::now()));
    try {
      s.processor(*frame);
      s.processed.fetch_add(1);
    } catch (const std::exception& e) {
      s.failed.fetch_add(1);
      std::lock_guard lock(error_mutex_);
      if (on_error_) on_error_(s.id, e.what());
    } catch (...) {
      s.failed.fetch_add(1);
      std::lock_guard lock(error_mutex_);
      if (on_error_) on_error_(s.id, "unknown exception");
    }
    s.busy_since.store(0);
  }
  // One frame per task, then to the back of the ready queue, so streams take turns. A frame
  // pushed between the pop above and this store is seen by one of the two checks below.
  s.scheduled.store(false);
  if (!s.queue.empty() && !s.scheduled.exchange(true)) schedule(s);
  finish_task();
}

void StreamScheduler::finish_task() {
  // Notify under the lock: the destructor may free the condition variable as soon as it can
  // take the lock and sees zero.
  std::lock_guard lock(tasks_mutex_);
  if (--active_tasks_ == 0) tasks_done_.notify_all();
}

std::size_t StreamScheduler::clear_queues() {
  std::shared_lock lock(streams_mutex_);
  std::size_t dropped = 0;
  for (const auto& s : streams_) dropped += s->queue.clear();
  return dropped;
}

DrainResult StreamScheduler::drain(std::chrono::milliseconds timeout,
                                   std::chrono::milliseconds grace) {
  {
    std::unique_lock input(input_mutex_);
    accepting_ = false;
  }
  DrainResult result;
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  std::unique_lock lock(tasks_mutex_);
  if (!tasks_done_.wait_until(lock, deadline, [&] { return active_tasks_ == 0; })) {
    lock.unlock();
    result.dropped = clear_queues();
    lock.lock();
    tasks_done_.wait_for(lock, grace, [&] { return active_tasks_ == 0; });
  }
  result.complete = active_tasks_ == 0;
  lock.unlock();
  if (!result.complete) result.in_flight = in_flight();
  return result;
}

void StreamScheduler::set_error_handler(ErrorHandler handler) {
  std::lock_guard lock(error_mutex_);
  on_error_ = std::move(handler);
}

std::size_t StreamScheduler::stream_count() const {
  std::shared_lock lock(streams_mutex_);
  return streams_.size();
}

const std::string& StreamScheduler::stream_id(Handle handle) const {
  return stream(handle).id;
}

SchedulerCounters StreamScheduler::counters(Handle handle) const {
  const Stream& s = stream(handle);
  SchedulerCounters c;
  c.submitted = s.queue.pushed();
  c.dropped = s.queue.dropped();
  c.queued = s.queue.size();
  c.processed = s.processed.load();
  c.failed = s.failed.load();
  return c;
}

std::size_t StreamScheduler::in_flight() const {
  std::shared_lock lock(streams_mutex_);
  return std::count_if(streams_.begin(), streams_.end(),
                       [](const auto& s) { return s->busy_since.load() != 0; });
}

std::chrono::steady_clock::duration StreamScheduler::longest_in_flight(
    std::chrono::steady_clock::time_point now) const {
  std::shared_lock lock(streams_mutex_);
  std::int64_t oldest = 0;
  for (const auto& s : streams_) {
    const std::int64_t since = s->busy_since.load();
    if (since != 0 && (oldest == 0 || since < oldest)) oldest = since;
  }
  if (oldest == 0) return std::chrono::steady_clock::duration::zero();
  return std::max(
      std::chrono::steady_clock::duration::zero(),
      std::chrono::steady_clock::duration(std::chrono::nanoseconds(to_ns(now) - oldest)));
}

}  // namespace litamin2::daemon

// Stream scheduler with fake processors: per-stream order, one frame at a time per stream,
// streams in parallel, drop-oldest when behind, drain and deadline, exceptions.

#include "litamin2/daemon/stream_scheduler.hpp"

#include <gtest/gtest.h>

#include <pthread.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

using namespace litamin2::daemon;
using namespace std::chrono_literals;

namespace {

Frame frame(std::uint64_t sequence) {
  Frame f;
  f.sequence = sequence;
  f.arrival = std::chrono::steady_clock::now();
  return f;
}

/// A gate the processors wait at until the test opens it (bounded wait).
class Gate {
 public:
  void open() {
    std::lock_guard lock(m_);
    open_ = true;
    cv_.notify_all();
  }
  bool wait(std::chrono::milliseconds timeout = 10s) {
    std::unique_lock lock(m_);
    return cv_.wait_for(lock, timeout, [&] { return open_; });
  }

 private:
  std::mutex m_;
  std::condition_variable cv_;
  bool open_ = false;
};

/// Waits (bounded) until `condition` holds.
template <class F>
bool eventually(F condition, std::chrono::milliseconds timeout = 10s) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!condition()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(1ms);
  }
  return true;
}

}  // namespace

TEST(StreamScheduler, PreservesOrderPerStream) {
  constexpr int kStreams = 4, kFrames = 300;
  StreamScheduler scheduler(2, kFrames);
  std::vector<std::vector<std::uint64_t>> seen(kStreams);
  std::vector<StreamScheduler::Handle> handles;
  for (int s = 0; s < kStreams; ++s)
    handles.push_back(scheduler.add_stream("s" + std::to_string(s), [&seen, s](Frame& f) {
      seen[s].push_back(f.sequence);  // one task at a time per stream: no lock needed
    }));
  // Two producer threads, each feeding two streams, interleaved.
  std::vector<std::thread> producers;
  for (int p = 0; p < 2; ++p)
    producers.emplace_back([&, p] {
      for (int i = 0; i < kFrames; ++i)
        for (int s = p; s < kStreams; s += 2) ASSERT_TRUE(scheduler.submit(handles[s], frame(i)));
    });
  for (auto& t : producers) t.join();
  const DrainResult result = scheduler.drain(20s);
  EXPECT_TRUE(result.complete);
  EXPECT_EQ(result.dropped, 0u);
  for (int s = 0; s < kStreams; ++s) {
    ASSERT_EQ(seen[s].size(), static_cast<std::size_t>(kFrames)) << "stream " << s;
    for (int i = 0; i < kFrames; ++i) EXPECT_EQ(seen[s][i], static_cast<std::uint64_t>(i));
    const SchedulerCounters c = scheduler.counters(handles[s]);
    EXPECT_EQ(c.submitted, static_cast<std::uint64_t>(kFrames));
    EXPECT_EQ(c.processed, static_cast<std::uint64_t>(kFrames));
    EXPECT_EQ(c.dropped, 0u);
  }
}

TEST(StreamScheduler, AtMostOneFramePerStreamInFlight) {
  constexpr int kStreams = 3, kFrames = 100;
  StreamScheduler scheduler(3, 16);
  std::vector<std::atomic<int>> busy(kStreams);
  std::atomic<int> overlaps{0};
  std::vector<StreamScheduler::Handle> handles;
  for (int s = 0; s < kStreams; ++s)
    handles.push_back(scheduler.add_stream("s" + std::to_string(s), [&, s](Frame&) {
      if (busy[s].fetch_add(1) != 0) ++overlaps;
      std::this_thread::sleep_for(200us);
      busy[s].fetch_sub(1);
    }));
  std::vector<std::thread> producers;
  for (int p = 0; p < 3; ++p)
    producers.emplace_back([&] {
      for (int i = 0; i < kFrames; ++i) {
        for (int s = 0; s < kStreams; ++s) scheduler.submit(handles[s], frame(i));
        std::this_thread::sleep_for(50us);
      }
    });
  for (auto& t : producers) t.join();
  EXPECT_TRUE(scheduler.drain(20s).complete);
  EXPECT_EQ(overlaps.load(), 0);
}

TEST(StreamScheduler, StreamsRunConcurrently) {
  // Each stream's first frame waits until the other stream's frame is running too: this
  // completes only if two frames of different streams are processed at the same time.
  StreamScheduler scheduler(2, 4);
  std::atomic<int> running{0};
  std::atomic<int> met{0};
  auto processor = [&](Frame&) {
    ++running;
    if (eventually([&] { return running.load() >= 2; }, 5s)) ++met;
  };
  const auto a = scheduler.add_stream("a", processor);
  const auto b = scheduler.add_stream("b", processor);
  scheduler.submit(a, frame(0));
  scheduler.submit(b, frame(0));
  EXPECT_TRUE(scheduler.drain(10s).complete);
  EXPECT_EQ(met.load(), 2);
}

TEST(StreamScheduler, FramesRunInAnArenaOfTheWorkerCount) {
  // A frame's nested parallel_for is bounded by the scheduler's thread count, whatever the
  // machine's core count, and runs on the scheduler's own (named) worker threads.
  for (const int threads : {1, 3}) {
    StreamScheduler scheduler(threads, 4);
    std::atomic<int> concurrency{0};
    std::string name;
    const auto s = scheduler.add_stream("a", [&](Frame&) {
      concurrency = tbb::this_task_arena::max_concurrency();
      char buffer[16] = {};
      pthread_getname_np(pthread_self(), buffer, sizeof(buffer));
      name = buffer;
    });
    scheduler.submit(s, frame(0));
    EXPECT_TRUE(scheduler.drain(10s).complete);
    EXPECT_EQ(concurrency.load(), threads);
    EXPECT_EQ(name, "stream-worker");
  }
}

TEST(StreamScheduler, SlowStreamDoesNotStallOthers) {
  StreamScheduler scheduler(2, 4);
  Gate gate;
  std::atomic<int> fast_done{0};
  const auto slow = scheduler.add_stream("slow", [&](Frame&) { gate.wait(); });
  const auto fast = scheduler.add_stream("fast", [&](Frame&) { ++fast_done; });
  scheduler.submit(slow, frame(0));
  for (int i = 0; i < 50; ++i) scheduler.submit(fast, frame(i));
  EXPECT_TRUE(eventually([&] { return fast_done.load() >= 4; }));
  gate.open();
  scheduler.drain(10s);
}

TEST(StreamScheduler, FallingBehindDropsOldestFrames) {
  StreamScheduler scheduler(1, 3);
  Gate gate;
  std::atomic<bool> started{false};
  std::vector<std::uint64_t> seen;
  const auto s = scheduler.add_stream("s", [&](Frame& f) {
    started = true;
    gate.wait();
    seen.push_back(f.sequence);
  });
  scheduler.submit(s, frame(0));
  ASSERT_TRUE(eventually([&] { return started.load(); }));
  for (int i = 1; i < 20; ++i) scheduler.submit(s, frame(i));  // 0 is in processing
  EXPECT_EQ(scheduler.counters(s).queued, 3u);
  EXPECT_EQ(scheduler.counters(s).dropped, 16u);
  gate.open();
  EXPECT_TRUE(scheduler.drain(10s).complete);
  EXPECT_EQ(seen, (std::vector<std::uint64_t>{0, 17, 18, 19}));
  const SchedulerCounters c = scheduler.counters(s);
  EXPECT_EQ(c.submitted, 20u);
  EXPECT_EQ(c.processed, 4u);
  EXPECT_EQ(c.dropped, 16u);
}

TEST(StreamScheduler, DrainFinishesQueuedFramesAndStopsInput) {
  StreamScheduler scheduler(2, 100);
  std::atomic<int> done{0};
  const auto s = scheduler.add_stream("s", [&](Frame&) {
    std::this_thread::sleep_for(1ms);
    ++done;
  });
  for (int i = 0; i < 50; ++i) scheduler.submit(s, frame(i));
  const DrainResult result = scheduler.drain(10s);
  EXPECT_TRUE(result.complete);
  EXPECT_EQ(result.dropped, 0u);
  EXPECT_EQ(done.load(), 50);
  EXPECT_FALSE(scheduler.submit(s, frame(50)));
  EXPECT_EQ(scheduler.counters(s).submitted, 50u);
  EXPECT_TRUE(scheduler.drain(0ms).complete);  // idempotent
}

TEST(StreamScheduler, DrainDeadlineDropsQueuedFrames) {
  StreamScheduler scheduler(1, 100);
  std::atomic<int> done{0};
  const auto s = scheduler.add_stream("s", [&](Frame&) {
    std::this_thread::sleep_for(20ms);
    ++done;
  });
  for (int i = 0; i < 40; ++i) scheduler.submit(s, frame(i));
  const auto start = std::chrono::steady_clock::now();
  const DrainResult result = scheduler.drain(50ms);
  const auto took = std::chrono::steady_clock::now() - start;
  EXPECT_TRUE(result.complete);  // the frame in processing finished within the grace time
  EXPECT_GT(result.dropped, 0u);
  EXPECT_LT(took, 1s);
  EXPECT_EQ(static_cast<std::size_t>(done.load()) + result.dropped, 40u);
  EXPECT_EQ(scheduler.counters(s).dropped, result.dropped);
}

TEST(StreamScheduler, ExceptionsAreCountedAndTheStreamGoesOn) {
  StreamScheduler scheduler(1, 16);
  std::mutex m;
  std::vector<std::string> errors;
  scheduler.set_error_handler([&](const std::string& stream, const std::string& what) {
    std::lock_guard lock(m);
    errors.push_back(stream + ": " + what);
  });
  std::atomic<int> ok{0};
  const auto s = scheduler.add_stream("s", [&](Frame& f) {
    if (f.sequence == 1) throw std::runtime_error("bad frame");
    ++ok;
  });
  for (int i = 0; i < 4; ++i) scheduler.submit(s, frame(i));
  EXPECT_TRUE(scheduler.drain(10s).complete);
  EXPECT_EQ(ok.load(), 3);
  EXPECT_EQ(scheduler.counters(s).failed, 1u);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0], "s: bad frame");
}

TEST(StreamScheduler, ReportsLongestFrameInProcessing) {
  StreamScheduler scheduler(1, 4);
  Gate gate;
  std::atomic<bool> started{false};
  const auto s = scheduler.add_stream("s", [&](Frame&) {
    started = true;
    gate.wait();
  });
  EXPECT_EQ(scheduler.longest_in_flight(), std::chrono::steady_clock::duration::zero());
  scheduler.submit(s, frame(0));
  ASSERT_TRUE(eventually([&] { return started.load(); }));
  std::this_thread::sleep_for(30ms);
  EXPECT_GE(scheduler.longest_in_flight(), 20ms);
  EXPECT_EQ(scheduler.in_flight(), 1u);
  gate.open();
  EXPECT_TRUE(scheduler.drain(10s).complete);
  EXPECT_EQ(scheduler.longest_in_flight(), std::chrono::steady_clock::duration::zero());
}

TEST(StreamScheduler, StreamsAddedWhileRunning) {
  StreamScheduler scheduler(2, 8);
  std::atomic<int> done{0};
  std::vector<std::thread> adders;
  for (int t = 0; t < 2; ++t)
    adders.emplace_back([&, t] {
      for (int i = 0; i < 10; ++i) {
        const auto h = scheduler.add_stream("t" + std::to_string(t) + "_" + std::to_string(i),
                                            [&](Frame&) { ++done; });
        for (int k = 0; k < 3; ++k) scheduler.submit(h, frame(k));
      }
    });
  for (auto& t : adders) t.join();
  EXPECT_TRUE(scheduler.drain(10s).complete);
  EXPECT_EQ(scheduler.stream_count(), 20u);
  EXPECT_EQ(done.load(), 60);
}

TEST(StreamScheduler, DestructorWithQueuedFramesReturns) {
  std::atomic<int> done{0};
  {
    StreamScheduler scheduler(1, 100);
    const auto s = scheduler.add_stream("s", [&](Frame&) {
      std::this_thread::sleep_for(5ms);
      ++done;
    });
    for (int i = 0; i < 100; ++i) scheduler.submit(s, frame(i));
  }
  EXPECT_LT(done.load(), 100);
}

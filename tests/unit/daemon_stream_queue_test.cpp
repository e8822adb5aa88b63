// Bounded per-stream queue: FIFO order, drop-oldest when full, counts, concurrent pushes.

#include "litamin2/daemon/stream_queue.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <thread>
#include <vector>

using litamin2::daemon::StreamQueue;

TEST(StreamQueue, FifoOrder) {
  StreamQueue<int> q(4);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(q.push(i), 0u);
  EXPECT_EQ(q.size(), 3u);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(q.pop().value(), i);
  EXPECT_FALSE(q.pop().has_value());
  EXPECT_TRUE(q.empty());
}

TEST(StreamQueue, FullQueueDropsOldestAndCounts) {
  StreamQueue<int> q(3);
  for (int i = 0; i < 10; ++i) q.push(i);
  EXPECT_EQ(q.size(), 3u);
  EXPECT_EQ(q.pushed(), 10u);
  EXPECT_EQ(q.dropped(), 7u);
  EXPECT_EQ(q.pop().value(), 7);
  EXPECT_EQ(q.pop().value(), 8);
  EXPECT_EQ(q.pop().value(), 9);
}

TEST(StreamQueue, PushReportsDrop) {
  StreamQueue<int> q(1);
  EXPECT_EQ(q.push(1), 0u);
  EXPECT_EQ(q.push(2), 1u);
  EXPECT_EQ(q.pop().value(), 2);
}

TEST(StreamQueue, ClearCountsDropped) {
  StreamQueue<int> q(5);
  for (int i = 0; i < 4; ++i) q.push(i);
  EXPECT_EQ(q.clear(), 4u);
  EXPECT_EQ(q.dropped(), 4u);
  EXPECT_TRUE(q.empty());
}

TEST(StreamQueue, ZeroCapacityIsRejected) {
  EXPECT_THROW(StreamQueue<int>(0), std::invalid_argument);
}

TEST(StreamQueue, MemoryIsBoundedByCapacity) {
  // Dropped elements are destroyed: live objects never exceed capacity (+1 being pushed).
  struct Counted {
    explicit Counted(std::shared_ptr<int> c) : count(std::move(c)) { ++*count; }
    Counted(Counted&& o) noexcept : count(std::move(o.count)) {}
    ~Counted() {
      if (count) --*count;
    }
    std::shared_ptr<int> count;
  };
  auto live = std::make_shared<int>(0);
  StreamQueue<Counted> q(2);
  for (int i = 0; i < 100; ++i) {
    q.push(Counted(live));
    EXPECT_LE(*live, 2);
  }
  EXPECT_EQ(q.dropped(), 98u);
}

TEST(StreamQueue, ConcurrentProducersAndConsumer) {
  StreamQueue<int> q(8);
  constexpr int kPerThread = 20000;
  std::atomic<bool> done{false};
  std::atomic<long> popped{0};
  std::thread consumer([&] {
    int last[2] = {-1, -1};
    while (!done.load() || !q.empty()) {
      if (auto v = q.pop()) {
        // Each producer's values come out in increasing order.
        const int producer = *v / kPerThread, value = *v % kPerThread;
        EXPECT_GT(value, last[producer]);
        last[producer] = value;
        ++popped;
      }
    }
  });
  std::vector<std::thread> producers;
  for (int p = 0; p < 2; ++p)
    producers.emplace_back([&, p] {
      for (int i = 0; i < kPerThread; ++i) q.push(p * kPerThread + i);
    });
  for (auto& t : producers) t.join();
  done = true;
  consumer.join();
  EXPECT_EQ(q.pushed(), 2u * kPerThread);
  EXPECT_EQ(static_cast<std::uint64_t>(popped.load()) + q.dropped(), 2u * kPerThread);
}

// PatchQueue: batches in order, a full queue makes the producer wait (never drops), close().

#include "litamin2/aggregator/patch_queue.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>

using namespace litamin2;
using namespace litamin2::aggregator;

namespace {

Keyframe keyframe(std::uint64_t id) {
  Keyframe kf;
  kf.key = {"s", id};
  return kf;
}

}  // namespace

TEST(PatchQueue, BatchesInOrder) {
  PatchQueue q(10);
  for (std::uint64_t i = 0; i < 5; ++i) ASSERT_TRUE(q.push(keyframe(i)));
  std::vector<Keyframe> out;
  EXPECT_EQ(q.pop_batch(out, 3, std::chrono::milliseconds(0)), 3u);
  EXPECT_EQ(q.pop_batch(out, 3, std::chrono::milliseconds(0)), 2u);
  ASSERT_EQ(out.size(), 5u);
  for (std::uint64_t i = 0; i < 5; ++i) EXPECT_EQ(out[i].key.id, i);
  EXPECT_EQ(q.pop_batch(out, 3, std::chrono::milliseconds(1)), 0u);
  EXPECT_EQ(q.high_water(), 5u);
}

TEST(PatchQueue, FullQueueWaitsInsteadOfDropping) {
  PatchQueue q(2);
  std::atomic<int> pushed{0};
  std::thread producer([&] {
    for (std::uint64_t i = 0; i < 100; ++i) {
      q.push(keyframe(i));
      ++pushed;
    }
  });
  std::vector<Keyframe> out;
  while (out.size() < 100) {
    q.pop_batch(out, 7, std::chrono::milliseconds(100));
    EXPECT_LE(q.size(), 2u);
  }
  producer.join();
  for (std::uint64_t i = 0; i < 100; ++i) EXPECT_EQ(out[i].key.id, i);
  EXPECT_LE(q.high_water(), 2u);
}

TEST(PatchQueue, CloseWakesAndDrains) {
  PatchQueue q(1);
  ASSERT_TRUE(q.push(keyframe(0)));
  std::thread producer([&] { EXPECT_FALSE(q.push(keyframe(1))); });  // waits: full
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  q.close();
  producer.join();
  std::vector<Keyframe> out;
  EXPECT_EQ(q.pop_batch(out, 10, std::chrono::seconds(5)), 1u);
  EXPECT_EQ(q.pop_batch(out, 10, std::chrono::seconds(5)), 0u);  // closed and empty: at once
  EXPECT_TRUE(q.closed());
}

#pragma once
/// The hand-off from the DDS listener (which only converts and enqueues) to the mapping thread:
/// a bounded multi-producer, single-consumer queue of keyframes. A full queue makes push() wait
/// (a reliable DDS reader then holds the writers back) rather than drop a patch: every patch
/// received must reach the store.

#include "litamin2/core/keyframe.hpp"

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <mutex>
#include <vector>

namespace litamin2::aggregator {

class PatchQueue {
 public:
  explicit PatchQueue(std::size_t capacity);

  /// Appends a keyframe, waiting while the queue is full. Returns false (dropping it) only
  /// when the queue is closed.
  bool push(Keyframe keyframe);
  /// Moves up to `max` keyframes into `out` (appended), waiting up to `timeout` for the first.
  /// Returns how many were taken (0 on timeout or when closed and empty).
  std::size_t pop_batch(std::vector<Keyframe>& out, std::size_t max,
                        std::chrono::milliseconds timeout);
  /// Wakes every waiter; later pushes fail, pops drain what is left.
  void close();

  std::size_t size() const;
  bool closed() const;
  std::size_t capacity() const { return capacity_; }
  /// Keyframes pushed so far, and the longest queue seen.
  std::size_t pushed() const;
  std::size_t high_water() const;

 private:
  const std::size_t capacity_;
  mutable std::mutex mutex_;
  std::condition_variable not_empty_;
  std::condition_variable not_full_;
  std::deque<Keyframe> items_;
  std::size_t pushed_ = 0;
  std::size_t high_water_ = 0;
  bool closed_ = false;
};

}  // namespace litamin2::aggregator

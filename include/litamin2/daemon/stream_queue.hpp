#pragma once
/// A bounded FIFO for one sensor stream: push never blocks, and when the queue is full the
/// oldest element is dropped and counted, so memory stays bounded whatever the input rate.

#include <cstddef>
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>
#include <stdexcept>

namespace litamin2::daemon {

template <class T>
class StreamQueue {
 public:
  /// Holds at most `capacity` (>= 1) elements.
  explicit StreamQueue(std::size_t capacity) : capacity_(capacity) {
    if (capacity_ == 0) throw std::invalid_argument("StreamQueue: capacity must be at least 1");
  }

  /// Appends `item`; if the queue was full, the oldest element is dropped first. Returns the
  /// number of elements dropped (0 or 1). Never blocks beyond the short internal lock.
  std::size_t push(T item) {
    std::optional<T> dropped;  // destroyed outside the lock
    {
      std::lock_guard lock(mutex_);
      if (items_.size() >= capacity_) {
        dropped.emplace(std::move(items_.front()));
        items_.pop_front();
        ++dropped_;
      }
      items_.push_back(std::move(item));
      ++pushed_;
    }
    return dropped ? 1 : 0;
  }

  /// Removes and returns the oldest element, or nothing if the queue is empty.
  std::optional<T> pop() {
    std::lock_guard lock(mutex_);
    if (items_.empty()) return std::nullopt;
    std::optional<T> item(std::move(items_.front()));
    items_.pop_front();
    return item;
  }

  /// Removes every element, counting them as dropped; returns how many.
  std::size_t clear() {
    std::deque<T> old;
    {
      std::lock_guard lock(mutex_);
      old.swap(items_);
      dropped_ += old.size();
    }
    return old.size();
  }

  std::size_t size() const {
    std::lock_guard lock(mutex_);
    return items_.size();
  }
  bool empty() const { return size() == 0; }
  std::size_t capacity() const { return capacity_; }
  /// Elements ever pushed.
  std::uint64_t pushed() const {
    std::lock_guard lock(mutex_);
    return pushed_;
  }
  /// Elements dropped because the queue was full, or by clear().
  std::uint64_t dropped() const {
    std::lock_guard lock(mutex_);
    return dropped_;
  }

 private:
  const std::size_t capacity_;
  mutable std::mutex mutex_;
  std::deque<T> items_;
  std::uint64_t pushed_ = 0;
  std::uint64_t dropped_ = 0;
};

}  // namespace litamin2::daemon

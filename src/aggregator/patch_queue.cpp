#include "litamin2/aggregator/patch_queue.hpp"

#include <algorithm>

namespace litamin2::aggregator {

PatchQueue::PatchQueue(std::size_t capacity) : capacity_(std::max<std::size_t>(capacity, 1)) {}

bool PatchQueue::push(Keyframe keyframe) {
  std::unique_lock lock(mutex_);
  not_full_.wait(lock, [&] { return closed_ || items_.size() < capacity_; });
  if (closed_) return false;
  items_.push_back(std::move(keyframe));
  ++pushed_;
  high_water_ = std::max(high_water_, items_.size());
  lock.unlock();
  not_empty_.notify_one();
  return true;
}

std::size_t PatchQueue::pop_batch(std::vector<Keyframe>& out, std::size_t max,
                                  std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  not_empty_.wait_for(lock, timeout, [&] { return closed_ || !items_.empty(); });
  const std::size_t n = std::min(max, items_.size());
  for (std::size_t i = 0; i < n; ++i) {
    out.push_back(std::move(items_.front()));
    items_.pop_front();
  }
  lock.unlock();
  if (n > 0) not_full_.notify_all();
  return n;
}

void PatchQueue::close() {
  {
    std::lock_guard lock(mutex_);
    closed_ = true;
  }
  not_empty_.notify_all();
  not_full_.notify_all();
}

std::size_t PatchQueue::size() const {
  std::lock_guard lock(mutex_);
  return items_.size();
}

bool PatchQueue::closed() const {
  std::lock_guard lock(mutex_);
  return closed_;
}

std::size_t PatchQueue::pushed() const {
  std::lock_guard lock(mutex_);
  return pushed_;
}

std::size_t PatchQueue::high_water() const {
  std::lock_guard lock(mutex_);
  return high_water_;
}

}  // namespace litamin2::aggregator

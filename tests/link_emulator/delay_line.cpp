#include "link_emulator/delay_line.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace litamin2::testing {

DelayLine::DelayLine(const LinkProfile& profile) : profile_(profile), random_(profile.seed) {
  const std::string error = validate(profile);
  if (!error.empty()) throw std::invalid_argument("link profile: " + error);
}

DelayLine::Admission DelayLine::push(Frame frame, Clock::time_point arrival) {
  ++counters_.received;
  if (profile_.loss_fraction > 0.0 &&
      std::bernoulli_distribution(profile_.loss_fraction)(random_)) {
    ++counters_.lost;
    return Admission::lost;
  }
  if (queue_.size() >= profile_.queue_limit_frames) {
    ++counters_.dropped_queue_full;
    return Admission::dropped_queue_full;
  }
  std::chrono::nanoseconds delay = profile_.delay;
  if (profile_.jitter.count() > 0) {
    delay += std::chrono::nanoseconds(std::uniform_int_distribution<std::int64_t>(
        -profile_.jitter.count(), profile_.jitter.count())(random_));
  }
  queue_.push(Entry{arrival + delay, next_sequence_++, std::move(frame)});
  counters_.max_queued = std::max(counters_.max_queued, queue_.size());
  return Admission::queued;
}

std::optional<DelayLine::Clock::time_point> DelayLine::next_release() const {
  if (queue_.empty()) return std::nullopt;
  return queue_.top().release;
}

bool DelayLine::pop_due(Clock::time_point now, Frame& out) {
  if (queue_.empty() || queue_.top().release > now) return false;
  // priority_queue::top() is const: the frame is moved out through a const_cast of the entry
  // about to be popped, which no comparison looks at again.
  Entry& entry = const_cast<Entry&>(queue_.top());
  if (last_forwarded_ && entry.sequence < *last_forwarded_) {
    ++counters_.reordered;
  } else {
    last_forwarded_ = entry.sequence;
  }
  out = std::move(entry.frame);
  queue_.pop();
  ++counters_.forwarded;
  counters_.bytes_forwarded += out.size();
  return true;
}

}  // namespace litamin2::testing

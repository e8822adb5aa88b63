#pragma once
/// Lets one log line through per period and counts the ones it held back, so that a flood of
/// bad messages costs one line per second, not one per message. Thread-safe.

#include <chrono>
#include <cstdint>
#include <mutex>
#include <optional>

namespace litamin2::service {

class LogRateLimiter {
 public:
  using Clock = std::chrono::steady_clock;

  explicit LogRateLimiter(Clock::duration period = std::chrono::seconds(1)) : period_(period) {}

  /// If a line may be logged now, returns how many were suppressed since the last one;
  /// otherwise counts this one as suppressed and returns nothing.
  std::optional<std::uint64_t> allow(Clock::time_point now = Clock::now()) {
    std::lock_guard lock(mutex_);
    if (last_ && now - *last_ < period_) {
      ++suppressed_;
      return std::nullopt;
    }
    last_ = now;
    const std::uint64_t suppressed = suppressed_;
    suppressed_ = 0;
    return suppressed;
  }

 private:
  const Clock::duration period_;
  std::mutex mutex_;
  std::optional<Clock::time_point> last_;
  std::uint64_t suppressed_ = 0;
};

}  // namespace litamin2::service

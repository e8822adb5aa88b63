#include "litamin2/service/metrics_board.hpp"

namespace litamin2::service {

void MetricsBoard::publish(std::string text) {
  auto shared = std::make_shared<const std::string>(std::move(text));
  std::lock_guard lock(mutex_);
  text_ = std::move(shared);
}

std::string MetricsBoard::text() const {
  std::shared_ptr<const std::string> shared;
  {
    std::lock_guard lock(mutex_);
    shared = text_;
  }
  return shared ? *shared : std::string();
}

void MetricsBoard::beat(Clock::time_point now) {
  last_beat_.store(now.time_since_epoch().count());
}

bool MetricsBoard::alive(Clock::time_point now, Clock::duration max_age) const {
  const Clock::rep beat = last_beat_.load();
  if (beat == 0) return true;  // starting: the loop has not begun
  return now - Clock::time_point(Clock::duration(beat)) <= max_age;
}

}  // namespace litamin2::service

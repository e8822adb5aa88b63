#include "litamin2/aggregator/full_pass_worker.hpp"

#include <algorithm>

namespace litamin2::aggregator {

bool full_pass_due(const FullPassConfig& config, std::size_t loops_since_last,
                   double seconds_since_last_end, double last_duration_s) {
  if (config.max_duty <= 0.0 || loops_since_last == 0) return false;
  const double rest = last_duration_s * (1.0 - config.max_duty) / config.max_duty;
  return seconds_since_last_end >= std::max(rest, config.min_interval_s);
}

FullPassWorker::FullPassWorker() : thread_([this] { run(); }) {}

FullPassWorker::~FullPassWorker() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

bool FullPassWorker::submit(mapping::FullPassProblem problem) {
  {
    std::lock_guard lock(mutex_);
    if (busy_) return false;
    busy_ = true;
    todo_ = std::move(problem);
  }
  wake_.notify_all();
  return true;
}

std::optional<mapping::FullPassProblem> FullPassWorker::take() {
  std::lock_guard lock(mutex_);
  if (!solved_) return std::nullopt;
  std::optional<mapping::FullPassProblem> out = std::move(solved_);
  solved_.reset();
  busy_ = false;
  return out;
}

bool FullPassWorker::busy() const {
  std::lock_guard lock(mutex_);
  return busy_;
}

void FullPassWorker::wait() {
  std::unique_lock lock(mutex_);
  done_.wait(lock, [&] { return !busy_ || solved_.has_value(); });
}

void FullPassWorker::run() {
  for (;;) {
    std::optional<mapping::FullPassProblem> problem;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || todo_.has_value(); });
      if (!todo_) return;  // stopping with nothing to do
      problem = std::move(todo_);
      todo_.reset();
    }
    mapping::GraphOptimizer::solve_full_pass(*problem);
    {
      std::lock_guard lock(mutex_);
      solved_ = std::move(problem);
    }
    done_.notify_all();
  }
}

}  // namespace litamin2::aggregator

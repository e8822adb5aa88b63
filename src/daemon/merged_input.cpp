#include "litamin2/daemon/merged_input.hpp"

namespace litamin2::daemon {

MergedInput::MergedInput(std::vector<Eigen::Isometry3d> extrinsics, ScanMergerConfig config,
                         StreamScheduler& scheduler, StreamScheduler::Handle handle)
    : merger_(std::move(extrinsics), config), scheduler_(scheduler), handle_(handle) {}

void MergedInput::add(std::size_t sensor, Frame scan) {
  // Submitted under the lock: frames reach the queue in the order they were merged.
  std::lock_guard lock(mutex_);
  submit(merger_.add(sensor, std::move(scan)));
}

void MergedInput::expire(Clock::time_point now) {
  std::lock_guard lock(mutex_);
  submit(merger_.expire(now));
}

void MergedInput::flush() {
  std::lock_guard lock(mutex_);
  submit(merger_.flush());
}

void MergedInput::restart() {
  std::lock_guard lock(mutex_);
  submit(merger_.restart());
}

ScanMergerCounters MergedInput::counters() const {
  std::lock_guard lock(mutex_);
  return merger_.counters();
}

void MergedInput::submit(std::vector<Frame> frames) {
  for (Frame& frame : frames) scheduler_.submit(handle_, std::move(frame));
}

}  // namespace litamin2::daemon

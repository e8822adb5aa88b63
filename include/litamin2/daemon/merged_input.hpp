#pragma once
/// The input side of a stream of several sensors: each sensor's reader hands its scans here
/// (from its DDS listener thread), they are merged (ScanMerger, under a mutex) and each merged
/// frame is queued on the stream's scheduler like a single sensor's scan. The main loop calls
/// expire() so that a frame whose other sensors stay silent is emitted after the merge timeout.

#include "litamin2/daemon/scan_merger.hpp"
#include "litamin2/daemon/stream_scheduler.hpp"

#include <mutex>

namespace litamin2::daemon {

class MergedInput {
 public:
  using Clock = ScanMerger::Clock;

  /// `scheduler` must outlive this. Throws std::invalid_argument as ScanMerger does.
  MergedInput(std::vector<Eigen::Isometry3d> extrinsics, ScanMergerConfig config,
              StreamScheduler& scheduler, StreamScheduler::Handle handle);

  /// A scan of sensor `sensor` (validated and converted by its listener).
  void add(std::size_t sensor, Frame scan);
  /// Queues the pending frame if it has waited merge_timeout_s.
  void expire(Clock::time_point now);
  /// Queues the pending frame (at shutdown, before the queues drain).
  void flush();
  /// A sensor's publisher restarted (its stamps may start over): ScanMerger::restart.
  void restart();
  /// A consistent copy of the merge counters.
  ScanMergerCounters counters() const;

 private:
  void submit(std::vector<Frame> frames);

  mutable std::mutex mutex_;
  ScanMerger merger_;
  StreamScheduler& scheduler_;
  const StreamScheduler::Handle handle_;
};

}  // namespace litamin2::daemon

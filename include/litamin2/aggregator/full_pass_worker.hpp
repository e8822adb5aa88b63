#pragma once
/// The background thread of the aggregator's full pass (mapping/graph_optimizer.hpp): the
/// mapping thread copies the problem out of the mapper (Mapper::full_pass_problem), hands it
/// here and goes on ingesting; it takes the solved problem back when it is done and applies
/// it (AggregatorCore::apply_full_pass). Ingest and place search never wait for it.
///
/// full_pass_due() is the policy: a pass when loops were checked since the last one, at most
/// `max_duty` of one core over time (after a pass of d seconds the next starts no sooner than
/// d (1 - max_duty) / max_duty later), and no sooner than min_interval_s after the last. The
/// callers count in d the mapping thread's copy and application (O(N) each) with the solve,
/// so passes grow rarer as the map grows and their cost per keyframe stays bounded.

#include "litamin2/mapping/graph_optimizer.hpp"

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <thread>

namespace litamin2::aggregator {

struct FullPassConfig {
  /// Share of one core the passes may use on average (0 = no background pass).
  double max_duty = 0.25;
  /// Seconds between the end of a pass and the start of the next, at least.
  double min_interval_s = 1.0;
  /// At shutdown, a last pass (synchronous) when loops were checked since the latest.
  bool on_stop = true;
};

/// Whether a pass should start now: idle, loops checked since the last, duty and interval
/// respected.
bool full_pass_due(const FullPassConfig& config, std::size_t loops_since_last,
                   double seconds_since_last_end, double last_duration_s);

class FullPassWorker {
 public:
  FullPassWorker();
  /// Waits for the pass in flight, then joins.
  ~FullPassWorker();
  FullPassWorker(const FullPassWorker&) = delete;
  FullPassWorker& operator=(const FullPassWorker&) = delete;

  /// Starts solving `problem`; false (and nothing done) while another is in flight.
  bool submit(mapping::FullPassProblem problem);
  /// The solved problem, once (empty while solving or idle).
  std::optional<mapping::FullPassProblem> take();
  /// A problem was submitted and not taken back yet.
  bool busy() const;
  /// Blocks until the problem in flight is solved.
  void wait();

 private:
  void run();

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable done_;
  std::optional<mapping::FullPassProblem> todo_;
  std::optional<mapping::FullPassProblem> solved_;
  bool busy_ = false;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace litamin2::aggregator

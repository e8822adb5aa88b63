// One direction of the test link emulator: frames go in with their arrival time and come out
// once their release time (arrival + delay +- jitter) has come, in release-time order (so a
// jitter larger than the gap between two frames reorders them), unless dropped at random
// (loss) or because LinkProfile::queue_limit_frames frames are already in flight. Every
// frame is counted in exactly one of forwarded, lost, dropped_queue_full, or still queued.
// The clock is the caller's: nothing here sleeps or reads the time.
#pragma once

#include "link_emulator/link_profile.hpp"

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <queue>
#include <random>
#include <vector>

namespace litamin2::testing {

struct DelayLineCounters {
  std::uint64_t received = 0;            // frames offered to push()
  std::uint64_t forwarded = 0;           // frames handed out by pop_due()
  std::uint64_t lost = 0;                // dropped at random (loss_fraction)
  std::uint64_t dropped_queue_full = 0;  // dropped: queue_limit_frames already in flight
  std::uint64_t reordered = 0;           // forwarded after a frame that arrived later
  std::uint64_t bytes_forwarded = 0;
  std::size_t max_queued = 0;  // most frames in flight at once
};

class DelayLine {
 public:
  using Clock = std::chrono::steady_clock;
  using Frame = std::vector<std::uint8_t>;
  enum class Admission { queued, lost, dropped_queue_full };

  // The profile must be valid (validate() empty); throws std::invalid_argument otherwise.
  explicit DelayLine(const LinkProfile& profile);

  Admission push(Frame frame, Clock::time_point arrival);
  // The earliest release time of the frames in flight; none when empty.
  std::optional<Clock::time_point> next_release() const;
  // Moves the next frame whose release time is <= now into `out`; false when there is none.
  bool pop_due(Clock::time_point now, Frame& out);
  std::size_t queued() const { return queue_.size(); }
  const DelayLineCounters& counters() const { return counters_; }

 private:
  struct Entry {
    Clock::time_point release;
    std::uint64_t sequence;  // arrival order: equal release times leave in arrival order
    Frame frame;
  };
  struct LaterFirst {
    bool operator()(const Entry& a, const Entry& b) const {
      return a.release != b.release ? a.release > b.release : a.sequence > b.sequence;
    }
  };

  LinkProfile profile_;
  std::mt19937_64 random_;
  std::priority_queue<Entry, std::vector<Entry>, LaterFirst> queue_;
  std::uint64_t next_sequence_ = 0;
  std::optional<std::uint64_t> last_forwarded_;  // the highest sequence forwarded so far
  DelayLineCounters counters_;
};

}  // namespace litamin2::testing

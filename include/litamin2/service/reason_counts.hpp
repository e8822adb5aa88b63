#pragma once
/// Counts of rejected inputs by reason ("bad_row_step": 3, "malformed_cdr": 1, ...), for a
/// status message: every rejection is counted under the short code of its conversion's error.
/// Thread-safe (listeners count, the status reads).

#include <cstdint>
#include <map>
#include <mutex>
#include <string>

namespace litamin2::service {

class ReasonCounts {
 public:
  void add(const std::string& reason, std::uint64_t n = 1) {
    std::lock_guard lock(mutex_);
    counts_[reason] += n;
    total_ += n;
  }
  std::uint64_t total() const {
    std::lock_guard lock(mutex_);
    return total_;
  }
  std::map<std::string, std::uint64_t> snapshot() const {
    std::lock_guard lock(mutex_);
    return counts_;
  }

 private:
  mutable std::mutex mutex_;
  std::map<std::string, std::uint64_t> counts_;
  std::uint64_t total_ = 0;
};

}  // namespace litamin2::service

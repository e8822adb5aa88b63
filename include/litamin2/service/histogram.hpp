#pragma once
/// A cumulative histogram with fixed upper bounds, as Prometheus histograms count: every
/// observation ever made, by the first bound it does not exceed (+Inf beyond the last), with
/// their sum. Not thread-safe: the owner guards it (StreamStats and MappingWorker under the lock
/// their status already takes).

#include <cstdint>
#include <vector>

namespace litamin2::service {

class Histogram {
 public:
  /// `upper_bounds` strictly increasing and finite (std::invalid_argument otherwise).
  explicit Histogram(std::vector<double> upper_bounds);

  /// A non-finite value is not counted (the caller counts it as invalid).
  void observe(double value);

  const std::vector<double>& upper_bounds() const { return bounds_; }
  /// Observations <= upper_bounds()[i], for each i (cumulative, as Prometheus's `le`).
  std::vector<std::uint64_t> cumulative_counts() const;
  std::uint64_t count() const { return count_; }
  double sum() const { return sum_; }

 private:
  std::vector<double> bounds_;
  /// Observations in (bounds_[i-1], bounds_[i]]; the last entry is (bounds_.back(), +Inf).
  std::vector<std::uint64_t> buckets_;
  std::uint64_t count_ = 0;
  double sum_ = 0.0;
};

/// Bounds for an arrival-to-result latency, seconds: 1 ms .. 10 s.
std::vector<double> latency_buckets_seconds();

}  // namespace litamin2::service

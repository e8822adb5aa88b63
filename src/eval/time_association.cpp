#include "litamin2/eval/time_association.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace litamin2::eval {

std::string time_series_error(const std::vector<double>& stamps) {
  for (std::size_t i = 0; i < stamps.size(); ++i) {
    if (!std::isfinite(stamps[i])) {
      return "timestamp " + std::to_string(i) + " is not finite";
    }
    if (i > 0 && !(stamps[i] > stamps[i - 1])) {
      return "timestamps are not strictly increasing at pose " + std::to_string(i);
    }
  }
  return {};
}

std::vector<TimePair> associate_by_time(const std::vector<double>& reference,
                                        const std::vector<double>& query, double max_difference) {
  if (!std::isfinite(max_difference) || max_difference < 0.0) {
    throw std::invalid_argument("associate_by_time: max_difference must be finite and >= 0");
  }
  for (const auto* series : {&reference, &query}) {
    const std::string error = time_series_error(*series);
    if (!error.empty()) throw std::invalid_argument("associate_by_time: " + error);
  }
  std::vector<TimePair> pairs;
  std::vector<double> pair_difference;  // |difference| of pairs[k]
  std::size_t r = 0;
  for (std::size_t q = 0; q < query.size() && !reference.empty(); ++q) {
    // Both series increase, so the nearest reference index never moves backwards.
    while (r + 1 < reference.size() &&
           std::abs(reference[r + 1] - query[q]) <= std::abs(reference[r] - query[q])) {
      ++r;
    }
    const double difference = std::abs(reference[r] - query[q]);
    if (difference > max_difference) continue;
    if (!pairs.empty() && pairs.back().reference_index == r) {
      if (difference < pair_difference.back()) {
        pairs.back().query_index = q;
        pair_difference.back() = difference;
      }
      continue;
    }
    pairs.push_back({r, q});
    pair_difference.push_back(difference);
  }
  return pairs;
}

}  // namespace litamin2::eval

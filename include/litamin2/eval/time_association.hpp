#pragma once
/// Pairing of two timestamped trajectories by time (as evo's --t_max_diff does), so that a
/// keyframe trajectory can be scored against full-rate ground truth.

#include <cstddef>
#include <string>
#include <vector>

namespace litamin2::eval {

/// One pair of indices: reference[reference_index] and query[query_index] are the same instant.
struct TimePair {
  std::size_t reference_index = 0;
  std::size_t query_index = 0;
};

/// Why a time series cannot be associated; empty when it can. A series must be finite and
/// strictly increasing (TUM files are written in time order; a repeated or reversed stamp is an
/// error in the file, not something to reorder silently).
std::string time_series_error(const std::vector<double>& stamps);

/// For each query stamp, the nearest reference stamp (ties: the later one); kept when |difference|
/// <= max_difference. A reference stamp claimed by several query stamps goes to the nearest of them
/// (ties: the earlier query), so every index appears at most once and the pairs are increasing in
/// both indices. Throws std::invalid_argument when either series fails time_series_error() or
/// max_difference is negative or not finite.
std::vector<TimePair> associate_by_time(const std::vector<double>& reference,
                                        const std::vector<double>& query, double max_difference);

}  // namespace litamin2::eval

#include "litamin2/eval/rpe.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "litamin2/eval/relative_error.hpp"

namespace litamin2::eval {

RpeResult compute_rpe(const std::vector<Eigen::Isometry3d>& ground_truth,
                      const std::vector<Eigen::Isometry3d>& estimate, std::size_t delta) {
  if (ground_truth.size() != estimate.size()) {
    throw std::invalid_argument("compute_rpe: ground truth has " +
                                std::to_string(ground_truth.size()) + " poses, estimate has " +
                                std::to_string(estimate.size()));
  }
  if (delta == 0) throw std::invalid_argument("compute_rpe: delta must be positive");

  RpeResult result;
  result.delta = delta;
  double t_sum = 0.0;
  double t_sum_sq = 0.0;
  double r_sum_sq = 0.0;
  for (std::size_t i = 0; i + delta < ground_truth.size(); ++i) {
    const RelativeError e =
        relative_error(ground_truth[i], ground_truth[i + delta], estimate[i], estimate[i + delta]);
    t_sum += e.translation;
    t_sum_sq += e.translation * e.translation;
    r_sum_sq += e.rotation * e.rotation;
    ++result.pairs;
  }
  if (result.pairs == 0) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    result.translation_rmse = result.translation_mean = result.rotation_rmse_deg = nan;
    return result;
  }
  const auto n = static_cast<double>(result.pairs);
  result.translation_rmse = std::sqrt(t_sum_sq / n);
  result.translation_mean = t_sum / n;
  result.rotation_rmse_deg = (180.0 / 3.14159265358979323846) * std::sqrt(r_sum_sq / n);
  return result;
}

}  // namespace litamin2::eval

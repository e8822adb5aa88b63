#include "litamin2/eval/ate.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "litamin2/eval/alignment.hpp"
#include "litamin2/eval/rotation_angle.hpp"

namespace litamin2::eval {
namespace {

constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;

double median(std::vector<double> values) {
  const std::size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + mid, values.end());
  const double upper = values[mid];
  if (values.size() % 2 == 1) return upper;
  const double lower = *std::max_element(values.begin(), values.begin() + mid);
  return 0.5 * (lower + upper);
}

}  // namespace

AteResult compute_ate(const std::vector<Eigen::Isometry3d>& ground_truth,
                      const std::vector<Eigen::Isometry3d>& estimate, AteAlignment alignment) {
  if (ground_truth.size() != estimate.size()) {
    throw std::invalid_argument("compute_ate: ground truth has " +
                                std::to_string(ground_truth.size()) + " poses, estimate has " +
                                std::to_string(estimate.size()));
  }
  if (ground_truth.empty()) throw std::invalid_argument("compute_ate: empty trajectories");

  Similarity3 transform;
  if (alignment != AteAlignment::kNone) {
    std::vector<Eigen::Vector3d> src;
    std::vector<Eigen::Vector3d> dst;
    src.reserve(estimate.size());
    dst.reserve(ground_truth.size());
    for (std::size_t i = 0; i < estimate.size(); ++i) {
      src.push_back(estimate[i].translation());
      dst.push_back(ground_truth[i].translation());
    }
    transform = umeyama_alignment(src, dst, alignment == AteAlignment::kSim3);
  }

  AteResult result;
  result.poses = ground_truth.size();
  result.alignment = transform.rigid();
  result.scale = transform.scale;

  std::vector<double> errors;
  errors.reserve(result.poses);
  double sum = 0.0;
  double sum_sq = 0.0;
  double rot_sum_sq = 0.0;
  for (std::size_t i = 0; i < result.poses; ++i) {
    const double e = (ground_truth[i].translation() - transform(estimate[i].translation())).norm();
    errors.push_back(e);
    sum += e;
    sum_sq += e * e;
    const double angle =
        rotation_angle_between(ground_truth[i].linear(), transform.rotation * estimate[i].linear());
    rot_sum_sq += angle * angle;
  }
  const auto n = static_cast<double>(result.poses);
  result.translation_rmse = std::sqrt(sum_sq / n);
  result.translation_mean = sum / n;
  result.translation_max = *std::max_element(errors.begin(), errors.end());
  result.translation_median = median(errors);
  result.rotation_rmse_deg = kRadToDeg * std::sqrt(rot_sum_sq / n);
  return result;
}

}  // namespace litamin2::eval

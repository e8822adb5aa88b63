#include "litamin2/eval/alignment.hpp"

#include <Eigen/SVD>
#include <stdexcept>

namespace litamin2::eval {

Eigen::Isometry3d Similarity3::rigid() const {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = rotation;
  t.translation() = translation;
  return t;
}

Similarity3 umeyama_alignment(const std::vector<Eigen::Vector3d>& src,
                              const std::vector<Eigen::Vector3d>& dst, bool with_scale) {
  if (src.size() != dst.size()) {
    throw std::invalid_argument("umeyama_alignment: point sets differ in size");
  }
  if (src.empty()) throw std::invalid_argument("umeyama_alignment: empty point sets");

  const auto n = static_cast<double>(src.size());
  Eigen::Vector3d mean_src = Eigen::Vector3d::Zero();
  Eigen::Vector3d mean_dst = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < src.size(); ++i) {
    mean_src += src[i];
    mean_dst += dst[i];
  }
  mean_src /= n;
  mean_dst /= n;

  // Cross-covariance sigma = 1/n sum (dst - mean_dst)(src - mean_src)^T and variance of src.
  Eigen::Matrix3d sigma = Eigen::Matrix3d::Zero();
  double var_src = 0.0;
  for (std::size_t i = 0; i < src.size(); ++i) {
    const Eigen::Vector3d s = src[i] - mean_src;
    sigma += (dst[i] - mean_dst) * s.transpose();
    var_src += s.squaredNorm();
  }
  sigma /= n;
  var_src /= n;

  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(sigma, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Vector3d s = Eigen::Vector3d::Ones();
  if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0.0) s(2) = -1.0;

  Similarity3 result;
  result.rotation = svd.matrixU() * s.asDiagonal() * svd.matrixV().transpose();
  result.scale = with_scale && var_src > 0.0 ? svd.singularValues().dot(s) / var_src : 1.0;
  result.translation = mean_dst - result.scale * (result.rotation * mean_src);
  return result;
}

}  // namespace litamin2::eval

#include "litamin2/store/record_codec.hpp"

#include "litamin2/core/value_checks.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace litamin2::store {

namespace {

// Byte-wise little-endian writes and reads: portable, and compilers turn them into plain
// loads and stores on little-endian hosts.
void put_u32(unsigned char* p, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<unsigned char>(v >> (8 * i));
}
void put_u64(unsigned char* p, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) p[i] = static_cast<unsigned char>(v >> (8 * i));
}
std::uint32_t get_u32(const unsigned char* p) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= static_cast<std::uint32_t>(p[i]) << (8 * i);
  return v;
}
std::uint64_t get_u64(const unsigned char* p) {
  std::uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v |= static_cast<std::uint64_t>(p[i]) << (8 * i);
  return v;
}

void put_f32(unsigned char* p, double value) {
  const float f = static_cast<float>(value);
  std::uint32_t bits;
  std::memcpy(&bits, &f, 4);
  put_u32(p, bits);
}
float get_f32(const unsigned char* p) {
  const std::uint32_t bits = get_u32(p);
  float f;
  std::memcpy(&f, &bits, 4);
  return f;
}
void put_f64(unsigned char* p, double value) {
  std::uint64_t bits;
  std::memcpy(&bits, &value, 8);
  put_u64(p, bits);
}
double get_f64(const unsigned char* p) {
  const std::uint64_t bits = get_u64(p);
  double d;
  std::memcpy(&d, &bits, 8);
  return d;
}

void check_size(const char* what, std::size_t size, std::size_t expected) {
  if (size != expected) {
    throw std::invalid_argument(std::string(what) + " blob has " + std::to_string(size) +
                                " bytes, expected " + std::to_string(expected));
  }
}

unsigned char* bytes(std::string& s) {
  return reinterpret_cast<unsigned char*>(s.data());
}

void check_pose(const char* what, const Eigen::Matrix<double, 3, 4>& m) {
  if (const auto why = checks::rotation_error(m.leftCols<3>()))
    throw std::invalid_argument(std::string(what) + ": rotation " + *why);
  if (const auto why = checks::position_error(m.col(3)))
    throw std::invalid_argument(std::string(what) + ": translation " + *why);
}

void check_matrix6(const char* what, const Matrix6d& m) {
  if (const auto why = checks::covariance_error<6>(m))
    throw std::invalid_argument(std::string(what) + " " + *why);
}

/// The distribution checks of the codec, on the values as stored (float mean, covariance triangle
/// and count).
void check_distribution(std::size_t index, const Eigen::Vector3d& mean, const Eigen::Matrix3d& cov,
                        std::int64_t count) {
  if (count < 0)  // (the message the store's callers have always seen)
    throw std::invalid_argument("a distribution has a negative point count " +
                                std::to_string(count) + " (distribution " + std::to_string(index) +
                                ")");
  const std::string what = "distribution " + std::to_string(index) + ": ";
  if (const auto why = checks::position_error(mean))
    throw std::invalid_argument(what + "mean " + *why);
  if (const auto why = checks::covariance_error<3>(cov))
    throw std::invalid_argument(what + "covariance " + *why);
  if (count < 1 || count > std::numeric_limits<int>::max())
    throw std::invalid_argument(what + "point count " + std::to_string(count) +
                                " is not in 1 .. 2^31 - 1");
}

/// The covariance of the stored upper triangle (xx, xy, xz, yy, yz, zz).
Eigen::Matrix3d from_triangle(const float* t) {
  Eigen::Matrix3d c;
  c << t[0], t[1], t[2],  //
      t[1], t[3], t[4],   //
      t[2], t[4], t[5];
  return c;
}

}  // namespace

std::string encode_pose(const Eigen::Isometry3d& pose) {
  std::string out(kPoseBytes, '\0');
  const Eigen::Matrix<double, 3, 4> m = pose.matrix().topRows<3>();
  check_pose("pose", m);
  for (int i = 0; i < 12; ++i) put_f64(bytes(out) + 8 * i, m.data()[i]);
  return out;
}

Eigen::Isometry3d decode_pose(const void* data, std::size_t size) {
  check_size("pose", size, kPoseBytes);
  const auto* p = static_cast<const unsigned char*>(data);
  Eigen::Matrix<double, 3, 4> m;
  for (int i = 0; i < 12; ++i) m.data()[i] = get_f64(p + 8 * i);
  check_pose("pose blob", m);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.matrix().topRows<3>() = m;
  return pose;
}

std::string encode_matrix6(const Matrix6d& m) {
  check_matrix6("6x6 matrix", m);
  std::string out(kMatrix6Bytes, '\0');
  for (int i = 0; i < 36; ++i) put_f64(bytes(out) + 8 * i, m.data()[i]);
  return out;
}

Matrix6d decode_matrix6(const void* data, std::size_t size) {
  check_size("6x6 matrix", size, kMatrix6Bytes);
  const auto* p = static_cast<const unsigned char*>(data);
  Matrix6d m;
  for (int i = 0; i < 36; ++i) m.data()[i] = get_f64(p + 8 * i);
  check_matrix6("6x6 matrix blob", m);
  return m;
}

std::string encode_distributions(const std::vector<Distribution>& distributions) {
  std::string out(distributions.size() * kDistributionBytes, '\0');
  unsigned char* p = bytes(out);
  for (std::size_t k = 0; k < distributions.size(); ++k) {
    const Distribution& d = distributions[k];
    const Eigen::Matrix3d& c = d.cov;
    const double values[9] = {d.mean.x(), d.mean.y(), d.mean.z(), c(0, 0), c(0, 1),
                              c(0, 2),    c(1, 1),    c(1, 2),    c(2, 2)};
    // Checked as given (bounded, so that the conversion to float is defined) and as they will be
    // read back, in float.
    check_distribution(k, d.mean, c, d.count);
    float stored[9];
    for (int i = 0; i < 9; ++i) stored[i] = static_cast<float>(values[i]);
    check_distribution(k, Eigen::Vector3f(stored[0], stored[1], stored[2]).cast<double>(),
                       from_triangle(stored + 3), d.count);
    for (int i = 0; i < 9; ++i) put_f32(p + 4 * i, values[i]);
    put_u32(p + 36, static_cast<std::uint32_t>(d.count));
    p += kDistributionBytes;
  }
  return out;
}

std::vector<Distribution> decode_distributions(const void* data, std::size_t size,
                                               const RegularizerConfig& regularizer) {
  if (size % kDistributionBytes != 0) {
    throw std::invalid_argument("distributions blob has " + std::to_string(size) +
                                " bytes, not a multiple of " + std::to_string(kDistributionBytes));
  }
  const auto* p = static_cast<const unsigned char*>(data);
  std::vector<Distribution> out(size / kDistributionBytes);
  for (std::size_t k = 0; k < out.size(); ++k) {
    Distribution& d = out[k];
    float v[9];
    for (int i = 0; i < 9; ++i) v[i] = get_f32(p + 4 * i);
    const std::uint32_t count = get_u32(p + 36);
    d.mean = Eigen::Vector3d(v[0], v[1], v[2]);
    const Eigen::Matrix3d raw = from_triangle(v + 3);
    check_distribution(k, d.mean, raw, count);
    regularize_for_terms(regularizer, raw, d.cov, d.shape_cov, d.shape_cov_inv);
    d.count = static_cast<int>(count);
    p += kDistributionBytes;
  }
  return out;
}

}  // namespace litamin2::store

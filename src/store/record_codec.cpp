#include "litamin2/store/record_codec.hpp"

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

}  // namespace

std::string encode_pose(const Eigen::Isometry3d& pose) {
  std::string out(kPoseBytes, '\0');
  const Eigen::Matrix<double, 3, 4> m = pose.matrix().topRows<3>();
  for (int i = 0; i < 12; ++i) put_f64(bytes(out) + 8 * i, m.data()[i]);
  return out;
}

Eigen::Isometry3d decode_pose(const void* data, std::size_t size) {
  check_size("pose", size, kPoseBytes);
  const auto* p = static_cast<const unsigned char*>(data);
  Eigen::Matrix<double, 3, 4> m;
  for (int i = 0; i < 12; ++i) m.data()[i] = get_f64(p + 8 * i);
  if (!m.allFinite()) throw std::invalid_argument("pose blob holds a non-finite value");
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.matrix().topRows<3>() = m;
  return pose;
}

std::string encode_matrix6(const Matrix6d& m) {
  std::string out(kMatrix6Bytes, '\0');
  for (int i = 0; i < 36; ++i) put_f64(bytes(out) + 8 * i, m.data()[i]);
  return out;
}

Matrix6d decode_matrix6(const void* data, std::size_t size) {
  check_size("6x6 matrix", size, kMatrix6Bytes);
  const auto* p = static_cast<const unsigned char*>(data);
  Matrix6d m;
  for (int i = 0; i < 36; ++i) m.data()[i] = get_f64(p + 8 * i);
  return m;
}

std::string encode_distributions(const std::vector<Distribution>& distributions) {
  std::string out(distributions.size() * kDistributionBytes, '\0');
  unsigned char* p = bytes(out);
  for (const Distribution& d : distributions) {
    if (d.count < 0) {
      throw std::invalid_argument("a distribution has a negative point count " +
                                  std::to_string(d.count));
    }
    const Eigen::Matrix3d& c = d.cov;
    const double values[9] = {d.mean.x(), d.mean.y(), d.mean.z(), c(0, 0), c(0, 1),
                              c(0, 2),    c(1, 1),    c(1, 2),    c(2, 2)};
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
  for (Distribution& d : out) {
    float v[9];
    for (int i = 0; i < 9; ++i) v[i] = get_f32(p + 4 * i);
    for (float x : v) {
      if (!std::isfinite(x)) throw std::invalid_argument("a distribution holds a non-finite value");
    }
    const std::uint32_t count = get_u32(p + 36);
    if (count > static_cast<std::uint32_t>(std::numeric_limits<int>::max())) {
      throw std::invalid_argument("a distribution has a point count " + std::to_string(count) +
                                  " out of range");
    }
    d.mean = Eigen::Vector3d(v[0], v[1], v[2]);
    Eigen::Matrix3d raw;
    raw << v[3], v[4], v[5],  //
        v[4], v[6], v[7],     //
        v[5], v[7], v[8];
    regularize_for_terms(regularizer, raw, d.cov, d.shape_cov, d.shape_cov_inv);
    d.count = static_cast<int>(count);
    p += kDistributionBytes;
  }
  return out;
}

std::string encode_descriptor(const mapping::PlaceDescriptor& d) {
  const std::size_t cells = static_cast<std::size_t>(d.rings) * static_cast<std::size_t>(d.sectors);
  if (d.rings < 0 || d.sectors < 0 || d.rings > 65535 || d.sectors > 65535 ||
      d.ring_key.size() != static_cast<std::size_t>(d.rings) || d.cells.size() != cells)
    throw std::invalid_argument("inconsistent place descriptor");
  std::string out(4 + 4 * d.ring_key.size() + cells, '\0');
  unsigned char* p = bytes(out);
  p[0] = static_cast<unsigned char>(d.rings & 0xff);
  p[1] = static_cast<unsigned char>(d.rings >> 8);
  p[2] = static_cast<unsigned char>(d.sectors & 0xff);
  p[3] = static_cast<unsigned char>(d.sectors >> 8);
  p += 4;
  for (float v : d.ring_key) {
    put_f32(p, v);
    p += 4;
  }
  std::memcpy(p, d.cells.data(), cells);
  return out;
}

mapping::PlaceDescriptor decode_descriptor(const void* data, std::size_t size) {
  const auto* p = static_cast<const unsigned char*>(data);
  if (size < 4) throw std::invalid_argument("descriptor blob too short");
  mapping::PlaceDescriptor d;
  d.rings = p[0] | (p[1] << 8);
  d.sectors = p[2] | (p[3] << 8);
  const std::size_t cells = static_cast<std::size_t>(d.rings) * static_cast<std::size_t>(d.sectors);
  check_size("descriptor", size, 4 + 4 * static_cast<std::size_t>(d.rings) + cells);
  p += 4;
  d.ring_key.resize(static_cast<std::size_t>(d.rings));
  for (float& v : d.ring_key) {
    v = get_f32(p);
    if (!std::isfinite(v)) throw std::invalid_argument("non-finite descriptor ring key");
    p += 4;
  }
  d.cells.assign(p, p + cells);
  return d;
}

}  // namespace litamin2::store
